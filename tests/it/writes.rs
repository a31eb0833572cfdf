//! Writing outputs (issue 13, A 1–3): no link is followed through a temporary name, a failed
//! build leaves OUT exactly as it was and names the path and the reason, stale temporary
//! files of a killed build are removed, and a killed build never leaves a partial file.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

use crate::common::tree::tree;

fn mini_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini")
}

/// A fresh scratch folder holding a copy of the mini font in `font/`.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("writes-{name}"));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(dir.join("font")).unwrap();
    for entry in fs::read_dir(mini_dir()).unwrap() {
        let path = entry.unwrap().path();
        fs::copy(&path, dir.join("font").join(path.file_name().unwrap())).unwrap();
    }
    dir
}

fn build(font: &Path, out: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .arg("build")
        .arg(font)
        .arg("-o")
        .arg(out)
        .output()
        .expect("xglyph runs")
}

fn names(tree: &[(String, Vec<u8>)]) -> Vec<&str> {
    tree.iter().map(|(n, _)| n.as_str()).collect()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A reference build of the mini font: what every output should hold.
fn reference(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let out = dir.join("reference");
    let result = build(&dir.join("font"), &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    outputs(&out)
}

/// [`tree`] with the output record's bytes left out (it stamps each output file with its
/// inode and times, which differ between folders), and the source memo's: only that they
/// exist is compared. The record's delta file is left out whole.
fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    tree(dir)
        .into_iter()
        // The record's delta is part of the record: whether a build writes one depends on
        // the record it found (a killed build's whole record makes the next one add a
        // delta), not on what it built.
        .filter(|(name, _)| name != xglyph::reuse::DELTA_FILE)
        .map(|(name, bytes)| {
            if name == xglyph::reuse::REUSE_FILE {
                (name, b"(the output record)".to_vec())
            } else if name == xglyph::source::MEMO_FILE {
                // Keyed by the sources' paths, which differ between the builds compared.
                (name, b"(the source memo)".to_vec())
            } else {
                (name, bytes)
            }
        })
        .collect()
}

#[cfg(unix)]
#[test]
fn links_planted_at_the_old_temporary_names_are_not_followed() {
    // The attack of the issue: the temporary name used to be `.NAME.tmpPID`, predictable
    // from the PID, which a shell knows before it execs the build.
    let dir = scratch("symlink");
    let want = reference(&dir);
    fs::write(dir.join("victim"), "precious").unwrap();
    let out = dir.join("out");
    fs::create_dir_all(out.join("svg")).unwrap();
    let script = "for n in sheet.png proof.png specimen.html MiniTest-Regular.svg \
                  MiniTest-Regular.ttf MiniTest-Regular.otf; do ln -s ../victim out/.$n.tmp$$; \
                  done; ln -s ../../victim out/svg/.A_.svg.tmp$$; \
                  exec \"$0\" build font -o out";
    let result = Command::new("bash")
        .args(["-c", script, env!("CARGO_BIN_EXE_xglyph")])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    assert_eq!(fs::read_to_string(dir.join("victim")).unwrap(), "precious");
    // The outputs are the reference outputs; the planted links are still links, untouched.
    let written = outputs(&out);
    let planted: Vec<_> = written.iter().filter(|(n, _)| n.contains(".tmp")).collect();
    assert_eq!(planted.len(), 7, "{:?}", names(&written));
    assert!(planted.iter().all(|(_, b)| b.starts_with(b"-> ")));
    let outputs: Vec<_> = written
        .into_iter()
        .filter(|(n, _)| !n.contains(".tmp"))
        .collect();
    assert_eq!(outputs, want);
}

/// Builds the mini font into `out` after `prepare` set OUT up, plus `extra` glyph files;
/// asserts the build fails with `message` (OUT being the placeholder `{out}`) and that OUT
/// is exactly as before.
fn fails_and_leaves_out_alone(
    name: &str,
    extra: &[(&str, String)],
    prepare: impl FnOnce(&Path),
    message: impl FnOnce(&Path) -> String,
) {
    let dir = scratch(name);
    let out = dir.join("out");
    prepare(&out);
    for (file, text) in extra {
        fs::write(dir.join("font").join(file), text).unwrap();
    }
    let before = tree(&out);
    let result = build(&dir.join("font"), &out);
    assert_eq!(result.status.code(), Some(1), "{}", stderr(&result));
    assert_eq!(String::from_utf8_lossy(&result.stdout), "");
    assert_eq!(stderr(&result), message(&out));
    assert_eq!(tree(&out), before, "OUT changed");
}

/// OUT filled by an earlier, good build.
fn built(out: &Path) {
    let result = build(&mini_dir(), out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
}

#[test]
fn a_glyph_name_too_long_for_a_file_name_fails_cleanly() {
    let long = "a".repeat(300);
    let glyph = format!(
        "name = \"{long}\"\nadvance = 500\n[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [100, 100, 0]]\n"
    );
    // Refused by the glyph-name rule (at most 63 characters) before anything is written.
    fails_and_leaves_out_alone("long-name", &[("long.toml", glyph)], built, |out| {
        let font = out.with_file_name("font");
        let shown: String = format!("name = \"{long}\"").chars().take(120).collect();
        format!(
            "{}/long.toml:1:8: error: glyph name `{long}` has 300 characters; glyph names are \
             1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule)\n  | {shown}…\n  \
             |        ^\nerror: 1 error in {}; nothing was written\n",
            font.display(),
            font.display()
        )
    });
}

#[test]
fn a_file_where_the_svg_folder_goes_fails_cleanly() {
    let prepare = |out: &Path| {
        fs::create_dir_all(out).unwrap();
        fs::write(out.join("svg"), "not a folder").unwrap();
        fs::write(out.join("sheet.png"), "an old sheet").unwrap();
    };
    fails_and_leaves_out_alone("svg-file", &[], prepare, |out| {
        format!(
            "error: cannot create the folder {}: a file of that name is in the way; {} is \
             unchanged\n",
            out.join("svg").display(),
            out.display()
        )
    });
}

#[test]
fn a_folder_where_proof_png_goes_fails_cleanly() {
    let prepare = |out: &Path| {
        built(out);
        fs::remove_file(out.join("proof.png")).unwrap();
        fs::create_dir_all(out.join("proof.png")).unwrap();
        fs::write(out.join("proof.png").join("keep.txt"), "mine").unwrap();
    };
    fails_and_leaves_out_alone("proof-folder", &[], prepare, |out| {
        format!(
            "error: cannot write {}: a folder of that name is in the way; {} is unchanged\n",
            out.join("proof.png").display(),
            out.display()
        )
    });
}

/// A 24 KB tmpfs mounted at a folder, unmounted on drop.
struct Tmpfs(PathBuf);

impl Tmpfs {
    fn mount(at: &Path, size: &str) -> Option<Tmpfs> {
        fs::create_dir_all(at).unwrap();
        let status = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(at)
            .output()
            .ok()?;
        status.status.success().then(|| Tmpfs(at.to_path_buf()))
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

#[test]
fn a_full_disk_fails_cleanly() {
    let dir = scratch("full");
    let want = reference(&dir);
    let out = dir.join("out");
    let Some(_mounted) = Tmpfs::mount(&out, "24k") else {
        eprintln!("SKIPPED a_full_disk_fails_cleanly: cannot mount a tmpfs (not root?)");
        return;
    };
    let result = build(&dir.join("font"), &out);
    assert_eq!(result.status.code(), Some(1), "{}", stderr(&result));
    // Which output meets the full disk depends on the file system's accounting; the
    // message names that output and the reason.
    let message = stderr(&result);
    let failed = names(&want)
        .into_iter()
        .find(|n| {
            message
                == format!(
                    "error: cannot write {}: no space left on device; {} is unchanged\n",
                    out.join(n).display(),
                    out.display()
                )
        })
        .unwrap_or_else(|| panic!("unexpected message: {message}"));
    eprintln!("full disk met at {failed}");
    assert_eq!(tree(&out), []);
}

#[test]
fn stale_temporary_files_of_a_killed_build_are_removed() {
    let dir = scratch("stale");
    let want = reference(&dir);
    let out = dir.join("out");
    fs::create_dir_all(out.join("svg")).unwrap();
    let mut child = Command::new("true").spawn().unwrap();
    child.wait().unwrap();
    let dead = child.id();
    let stale = [
        format!(".xglyph-{dead}-Ab3dE6gH9j.tmp"),
        format!(".xglyph-{dead}-0123456789.old"),
        format!("svg/.xglyph-{dead}-zzzzzzzzzz.tmp"),
        // The naming of earlier versions, for an output of this build.
        format!("svg/.A_.svg.tmp{dead}"),
        format!(".sheet.png.tmp{dead}"),
    ];
    let mine = [
        "notes.txt".to_string(),
        format!(".xglyph-{dead}-Ab3dE6gH9j.tmp.txt"),
        format!(".xglyph-{dead}-short.tmp"),
        format!(".unrelated.png.tmp{dead}"),
        ".sheet.png.tmp-draft".to_string(),
        // A build that is still running (this test's own PID stands in for it).
        format!(".xglyph-{}-Ab3dE6gH9j.tmp", std::process::id()),
    ];
    for name in stale.iter().chain(&mine) {
        fs::write(out.join(name), "leftover").unwrap();
    }
    let result = build(&dir.join("font"), &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    let after = tree(&out);
    let mut expected: Vec<String> = names(&want).iter().map(|n| n.to_string()).collect();
    expected.extend(mine.iter().cloned());
    expected.sort();
    assert_eq!(names(&after), expected);
}

#[test]
fn a_killed_build_leaves_only_whole_files() {
    let dir = scratch("killed");
    let want = reference(&dir);
    let out = dir.join("out");
    let start = Instant::now();
    built(&dir.join("timing"));
    let took = start.elapsed();
    // Kill builds at delays spread over (and a little past) a whole build.
    let steps = 24;
    let mut caught_writing = 0;
    for k in 0..steps {
        let mut child = Command::new(env!("CARGO_BIN_EXE_xglyph"))
            .arg("build")
            .arg(dir.join("font"))
            .arg("-o")
            .arg(&out)
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(took.mul_f64(1.2 * k as f64 / steps as f64));
        let _ = child.kill();
        child.wait().unwrap();
        let now = tree(&out);
        for (name, bytes) in &now {
            let hidden = Path::new(name)
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.'));
            if hidden {
                caught_writing += 1;
                continue;
            }
            let whole = want.iter().find(|(n, _)| n == name).map(|(_, b)| b);
            assert_eq!(
                whole,
                Some(bytes),
                "{name} is not a whole output (kill {k})"
            );
        }
    }
    eprintln!("{caught_writing} temporary files seen after {steps} kills");
    // The next build completes and removes what the killed ones left.
    let result = build(&dir.join("font"), &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    assert_eq!(outputs(&out), want);
}

/// Every regular file under `dir` by relative path: its inode (a replaced file gets a new
/// one) and its bytes.
#[cfg(unix)]
fn inodes(dir: &Path) -> std::collections::BTreeMap<String, (u64, Vec<u8>)> {
    use std::os::unix::fs::MetadataExt;
    tree(dir)
        .into_iter()
        .filter_map(|(name, bytes)| {
            let meta = fs::symlink_metadata(dir.join(&name)).unwrap();
            meta.is_file().then(|| (name, (meta.ino(), bytes)))
        })
        .collect()
}

#[cfg(unix)]
#[test]
fn a_rebuild_replaces_only_the_files_whose_bytes_changed() {
    let dir = scratch("unchanged");
    let out = dir.join("out");
    let font = dir.join("font");
    // The sources settled, so that the first build stamps them in its source memo (a
    // file changed less than `SETTLED` ago is stamped by the next build, which then
    // rewrites the memo).
    std::thread::sleep(xglyph::write::SETTLED * 2);
    let result = build(&font, &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    let first = inodes(&out);
    // Nothing changed: no output is replaced (same inode), so nothing is written but the
    // output record (it now stamps the files, too fresh to stamp after the first build).
    let result = build(&font, &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    // (The record may be written whole, or as a delta file when the first build could
    // stamp most outputs already.)
    let without_record = |mut files: std::collections::BTreeMap<String, (u64, Vec<u8>)>| {
        files.remove(xglyph::reuse::REUSE_FILE);
        files.remove(xglyph::reuse::DELTA_FILE);
        files
    };
    assert_eq!(without_record(inodes(&out)), without_record(first.clone()));
    // One glyph edited (the apex of `A` moves up by 10 units).
    let a = font.join("A_.toml");
    let source = fs::read_to_string(&a).unwrap();
    fs::write(
        &a,
        source.replace(
            "[280, 700, 0], [360, 700, 0]",
            "[280, 710, 0], [360, 710, 0]",
        ),
    )
    .unwrap();
    let result = build(&font, &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    let second = inodes(&out);
    // The result is what a build into an empty folder writes (the fit cache aside: it
    // keeps the old fit of `A` too).
    // The records (fit cache, output record, source memo and their delta files).
    let not_cache = |n: &String| !n.starts_with(".xglyph-");
    reference(&dir);
    let fresh: Vec<_> = inodes(&dir.join("reference"))
        .into_iter()
        .filter(|(n, _)| not_cache(n))
        .map(|(n, (_, b))| (n, b))
        .collect();
    let rebuilt: Vec<_> = second
        .iter()
        .filter(|(n, _)| not_cache(n))
        .map(|(n, (_, b))| (n.clone(), b.clone()))
        .collect();
    assert!(rebuilt == fresh, "the rebuild differs from a fresh build");
    let (mut replaced, mut kept) = (Vec::new(), Vec::new());
    for (name, (ino, bytes)) in second.iter().filter(|(n, _)| not_cache(n)) {
        let (old_ino, old_bytes) = &first[name];
        if bytes == old_bytes {
            assert_eq!(ino, old_ino, "{name} has the same bytes but was replaced");
            kept.push(name.as_str());
        } else {
            assert_ne!(ino, old_ino, "{name} changed in place, not replaced");
            replaced.push(name.as_str());
        }
    }
    // `A` is in its own SVG, the fonts and the images; `o` and `V` are not touched.
    for name in [
        "svg/A_.svg",
        "sheet.png",
        "proof.png",
        "MiniTest-Regular.ttf",
    ] {
        assert!(
            replaced.contains(&name),
            "{name} not rewritten: {replaced:?}"
        );
    }
    for name in [
        "svg/o.svg",
        "svg/V_.svg",
        "MiniTest-Regular.ufo/glyphs/o.glif",
    ] {
        assert!(kept.contains(&name), "{name} rewritten: {kept:?}");
    }
}

#[test]
fn a_build_into_a_new_nested_folder_writes_the_outputs_and_no_temporary_name() {
    let dir = scratch("new-nested");
    let want = reference(&dir);
    // A staged tree of a killed build (a PID that is gone), next to where OUT goes.
    let mut child = Command::new("true").spawn().unwrap();
    child.wait().unwrap();
    let stale = dir.join(format!("new/.xglyph-{}-Ab3dE6gH9j.dir", child.id()));
    fs::create_dir_all(stale.join("svg")).unwrap();
    fs::write(stale.join("svg/A_.svg"), "half written").unwrap();
    let out = dir.join("new/deeper/out");
    let result = build(&dir.join("font"), &out);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    assert_eq!(outputs(&out), want);
    // `new/` held the stale tree, removed when this build staged its own tree there; no
    // temporary name is left anywhere.
    let mut expected = vec!["deeper".to_string(), "deeper/out".to_string()];
    expected.extend(names(&want).iter().map(|n| format!("deeper/out/{n}")));
    assert_eq!(names(&tree(&dir.join("new"))), expected);
}
