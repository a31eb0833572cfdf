//! What `xglyph import` writes: file names that never take `font.toml` or `kerning.toml`,
//! a temporary folder renamed into place (a full disk leaves nothing), progress only on a
//! terminal, the same bytes whatever the thread count, and fonts from a collection.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::cli::{import, import_ok, xglyph, xglyph_env};
use crate::common::temp::TempFolder;

const DEJAVU: &str = "tests/fixtures/import/DejaVuSans.ttf";
const RING: &str = "tests/fixtures/import/ring.svg";
/// Debian fonts-wqy-zenhei: a collection of three fonts (Zen Hei, Zen Hei Mono, Sharp).
const WQY: &str = "/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc";

fn temp_dir(name: &str) -> TempFolder {
    TempFolder::new(&format!("import-out-{name}"))
}

/// File names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn glyph_files_never_take_reserved_names() {
    let dir = temp_dir("reserved");
    // SVG drawings named font.svg and kerning.svg become glyphs `font` and `kerning`.
    for name in ["font.svg", "kerning.svg"] {
        std::fs::copy(RING, dir.join(name)).unwrap();
    }
    let out = dir.join("icons");
    let stdout = import_ok(
        &[
            dir.join("font.svg").to_str().unwrap(),
            dir.join("kerning.svg").to_str().unwrap(),
        ],
        &out,
    );
    assert!(
        stdout.ends_with(&format!("wrote 3 files to {}\n", out.display())),
        "{stdout}"
    );
    assert_eq!(listing(&out), ["_font.toml", "_kerning.toml", "font.toml"]);
    let glyph = std::fs::read_to_string(out.join("_font.toml")).unwrap();
    assert!(
        glyph.starts_with("name = \"font\"\nunicode = 0xE000\n"),
        "{glyph}"
    );
    assert!(std::fs::read_to_string(out.join("font.toml"))
        .unwrap()
        .starts_with("family = \"Imported Icons\"\n"));
    let (code, stdout, _) = xglyph(&["check", out.to_str().unwrap()]);
    assert_eq!((code, stdout.as_str()), (0, "0 errors, 0 warnings\n"));

    // A font whose glyphs are named `font` and `kerning`: DejaVu Sans with two of its
    // stored post-table names overwritten in place (`hbar` -> `font`, `amacron` ->
    // `kerning`, same lengths).
    let mut data = std::fs::read(DEJAVU).unwrap();
    for (from, to) in [
        (&b"\x04hbar"[..], &b"\x04font"[..]),
        (b"\x07amacron", b"\x07kerning"),
    ] {
        let at = data
            .windows(from.len())
            .position(|w| w == from)
            .expect("the name is stored once in DejaVu's post table");
        data[at..at + to.len()].copy_from_slice(to);
    }
    let renamed = dir.join("renamed.ttf");
    std::fs::write(&renamed, data).unwrap();
    let out = dir.join("font");
    let stdout = import_ok(&[renamed.to_str().unwrap(), "--glyphs", "ħ,ā,a"], &out);
    assert!(
        stdout.ends_with(&format!("wrote 4 files to {}\n", out.display())),
        "{stdout}"
    );
    assert_eq!(
        listing(&out),
        ["_font.toml", "_kerning.toml", "a.toml", "font.toml"]
    );
    let glyph = std::fs::read_to_string(out.join("_kerning.toml")).unwrap();
    assert!(
        glyph.starts_with("name = \"kerning\"\nunicode = 0x0101\n"),
        "{glyph}"
    );
    let (code, stdout, _) = xglyph(&["check", out.to_str().unwrap()]);
    assert_eq!((code, stdout.as_str()), (0, "0 errors, 0 warnings\n"));
}

#[test]
fn a_full_disk_leaves_nothing_and_the_rerun_works() {
    let dir = temp_dir("full");
    let mnt = dir.join("mnt");
    std::fs::create_dir_all(&mnt).unwrap();
    let mounted = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=40k", "tmpfs"])
        .arg(&mnt)
        .output()
        .is_ok_and(|o| o.status.success());
    if !mounted {
        eprintln!("skipped: cannot mount a 40 KB tmpfs here (needs root)");
        return;
    }
    struct Unmount<'a>(&'a Path);
    impl Drop for Unmount<'_> {
        fn drop(&mut self) {
            let _ = Command::new("umount").arg(self.0).status();
        }
    }
    let _guard = Unmount(&mnt);
    // 63 files of at least one 4 KB page each do not fit in 40 KB.
    let out = mnt.join("dejavu");
    let (code, stdout, err) = import(&[DEJAVU, "--glyphs", "A-Z,a-z,0-9"], &out);
    assert_eq!((code, stdout.as_str()), (1, ""));
    assert!(
        err.starts_with(&format!("error: {}/", out.display()))
            && err.ends_with(": No space left on device (os error 28)\n"),
        "{err}"
    );
    assert!(err.contains(".toml: cannot write: "), "{err}");
    assert!(listing(&mnt).is_empty(), "left behind: {:?}", listing(&mnt));
    // The rerun into the same place with fewer glyphs works.
    let stdout = import_ok(&[DEJAVU, "--glyphs", "A-C"], &out);
    assert!(
        stdout.ends_with(&format!("wrote 5 files to {}\n", out.display())),
        "{stdout}"
    );
    assert_eq!(listing(&mnt), ["dejavu"]);
    // DejaVu kerns A-A, A-C and B-C.
    assert_eq!(
        listing(&out),
        ["A_.toml", "B_.toml", "C_.toml", "font.toml", "kerning.toml"]
    );
}

#[test]
fn progress_only_on_a_terminal() {
    let dir = temp_dir("progress");
    // Not a terminal (a pipe): nothing on stderr.
    import_ok(&[DEJAVU, "--glyphs", "a-c"], &dir.join("piped"));
    // A terminal: util-linux `script` runs the command on a pseudo-terminal.
    if Command::new("script").arg("--version").output().is_err() {
        eprintln!("skipped the terminal half: `script` (util-linux) is not installed");
        return;
    }
    let command = format!(
        "{} import {DEJAVU} --glyphs a-c -o {} >/dev/null",
        env!("CARGO_BIN_EXE_xglyph"),
        dir.join("tty").display()
    );
    let out = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let seen = String::from_utf8_lossy(&out.stdout);
    assert_eq!(seen, "\r1/3 glyphs\r2/3 glyphs\r3/3 glyphs\r\n");
}

#[test]
fn the_same_bytes_on_one_thread_and_on_four() {
    let dir = temp_dir("threads");
    let mut outputs = Vec::new();
    for threads in ["1", "4"] {
        let out = dir.join(format!("t{threads}"));
        let (code, stdout, err) = xglyph_env(
            &[
                "import",
                DEJAVU,
                "--glyphs",
                "a-z,&,@",
                "-o",
                out.to_str().unwrap(),
            ],
            &[("RAYON_NUM_THREADS", threads)],
        );
        assert_eq!((code, err.as_str()), (0, ""));
        let files: Vec<(String, Vec<u8>)> = listing(&out)
            .into_iter()
            .map(|name| {
                let bytes = std::fs::read(out.join(&name)).unwrap();
                (name, bytes)
            })
            .collect();
        // 28 glyphs, the five ligatures `liga` makes of them, font.toml, kerning.toml and
        // features.fea.
        assert_eq!(files.len(), 36);
        outputs.push((stdout.replace(out.to_str().unwrap(), "OUT"), files));
    }
    assert!(
        outputs[0] == outputs[1],
        "the outputs differ between 1 and 4 threads"
    );
}

#[test]
fn fonts_from_a_collection() {
    if !Path::new(WQY).exists() {
        eprintln!("skipped: {WQY} is not installed (Debian fonts-wqy-zenhei)");
        return;
    }
    let dir = temp_dir("ttc");
    // The family is the font's US English name record, though its Chinese ones come first.
    for (face, family) in [("0", "WenQuanYi Zen Hei"), ("1", "WenQuanYi Zen Hei Mono")] {
        let out = dir.join(format!("face{face}"));
        import_ok(&[WQY, "--face", face, "--glyphs", "一"], &out);
        let info = std::fs::read_to_string(out.join("font.toml")).unwrap();
        assert!(
            info.starts_with(&format!("family = \"{family}\"\n")),
            "{info}"
        );
        assert_eq!(listing(&out), ["font.toml", "uni4E_00.toml"]);
    }
    // A face the file does not have: exit 1, the message, nothing on stdout, nothing written.
    let wrong_faces = [
        (
            WQY,
            "3",
            "none",
            format!("error: {WQY}: --face 3: this collection has 3 fonts (--face 0 to 2)\n"),
        ),
        (
            DEJAVU,
            "1",
            "single",
            format!("error: {DEJAVU}: --face 1: this is a single font, not a collection\n"),
        ),
    ];
    for (font, face, out, message) in wrong_faces {
        let (code, stdout, err) = import(&[font, "--face", face], &dir.join(out));
        assert_eq!((code, stdout.as_str(), err), (1, "", message));
    }
    assert!(!dir.join("none").exists() && !dir.join("single").exists());
}

/// Every file `dir` holds, by name, with its bytes.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    listing(dir)
        .into_iter()
        .map(|name| {
            let bytes = std::fs::read(dir.join(&name)).unwrap();
            (name, bytes)
        })
        .collect()
}

/// The one file in `dir` whose name ends with `ext`.
fn only_with_ext(dir: &Path, ext: &str) -> PathBuf {
    let found: Vec<String> = listing(dir)
        .into_iter()
        .filter(|n| n.ends_with(ext))
        .collect();
    assert_eq!(found.len(), 1, "{ext} in {}: {found:?}", dir.display());
    dir.join(&found[0])
}

#[test]
fn web_fonts_come_in_as_the_fonts_they_wrap() {
    let dir = temp_dir("webfonts");
    // xglyph's own WOFF2 (glyf and loca transformed) against its TTF of the same build.
    let src = dir.join("src");
    import_ok(&[DEJAVU, "--glyphs", "a-z,&"], &src);
    let built = dir.join("built");
    let (code, _, err) = xglyph(&[
        "build",
        src.to_str().unwrap(),
        "-o",
        built.to_str().unwrap(),
    ]);
    assert_eq!((code, err.as_str()), (0, ""));
    let mut pairs = vec![(
        only_with_ext(&built, ".ttf"),
        only_with_ext(&built, ".woff2"),
    )];
    // WOFF (zlib) and WOFF2 as fontTools writes them, from the DejaVu fixture itself.
    let have_tools = crate::common::tools::available(
        crate::common::tools::python_imports("fontTools, brotli"),
        "fontTools with brotli",
        "pip install fonttools brotli",
    );
    if have_tools {
        for flavor in ["woff", "woff2"] {
            let packed = dir.join(format!("DejaVuSans.{flavor}"));
            let script = "import sys; from fontTools.ttLib import TTFont\n\
                          f = TTFont(sys.argv[1]); f.flavor = sys.argv[2]; f.save(sys.argv[3])";
            crate::common::tools::run(
                Command::new("python3")
                    .args(["-c", script, DEJAVU, flavor])
                    .arg(&packed),
            );
            pairs.push((PathBuf::from(DEJAVU), packed));
        }
    }
    for (i, (plain, packed)) in pairs.iter().enumerate() {
        let (a, b) = (
            dir.join(format!("plain{i}")),
            dir.join(format!("packed{i}")),
        );
        let args = |font: &Path| {
            vec![
                font.to_str().unwrap().to_string(),
                "--glyphs".into(),
                "a-z,&".into(),
            ]
        };
        let plain_args = args(plain);
        let packed_args = args(packed);
        let report = import_ok(
            &plain_args.iter().map(String::as_str).collect::<Vec<_>>(),
            &a,
        );
        let packed_report = import_ok(
            &packed_args.iter().map(String::as_str).collect::<Vec<_>>(),
            &b,
        );
        // 27 glyphs and the five ligatures `liga` makes of them.
        assert!(report.contains("total: 32 glyphs"), "{report}");
        assert_eq!(
            packed_report.replace(b.to_str().unwrap(), "OUT"),
            report.replace(a.to_str().unwrap(), "OUT"),
            "{}",
            packed.display()
        );
        assert!(
            contents(&a) == contents(&b),
            "{} differs from {}",
            packed.display(),
            plain.display()
        );
    }
    // A damaged WOFF2: exit 1, the file and what is wrong, nothing written.
    let woff2 = std::fs::read(&pairs[0].1).unwrap();
    let cut = dir.join("cut.woff2");
    std::fs::write(&cut, &woff2[..woff2.len() / 2]).unwrap();
    let err = crate::common::cli::import_fails(&[cut.to_str().unwrap()], &dir.join("cut"));
    assert_eq!(
        err,
        format!(
            "error: {}: cannot unpack this WOFF2 file; it may be damaged\n",
            cut.display()
        )
    );
}
