use xglyph::compatible::fit_compatible;
use xglyph::fit::fit_contour;
#[path = "../tests/it/common/masters.rs"]
mod masters;
static mut KINK: f64 = 0.0;
static mut JOINS: usize = 0;
static mut K1: usize = 0;
static mut K5: usize = 0;
#[allow(static_mut_refs)]
fn main() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (font, _) = xglyph::source::load_font(&dir).unwrap();
    let tol = font.info.tolerance;
    let only: Vec<String> = std::env::args().skip(1).collect();
    let (mut a, mut b, mut c, mut d) = (0, 0, 0, 0);
    let t0 = std::time::Instant::now();
    let (mut ts, mut tc) = (0.0, 0.0);
    for g in &font.glyphs {
        if !only.is_empty() && !only.contains(&g.name) {
            continue;
        }
        let (mut sl, mut sb, mut c2, mut c11) = (0, 0, 0, 0);
        let mut worst: f64 = 0.0;
        for contour in &g.contours {
            let l = contour.spline();
            let bo = masters::bold(
                l,
                30.0,
                std::env::var("XG_S").map_or(0.8, |v| v.parse().unwrap()),
            )
            .unwrap();
            let t = std::time::Instant::now();
            sl += fit_contour(l, tol).path.segments().count();
            ts += t.elapsed().as_secs_f64();
            sb += fit_contour(&bo, tol).path.segments().count();
            c2 += fit_compatible(&[l, &bo], &masters::evenly_spaced(2), tol)
                .unwrap()
                .segments;
            let t = std::time::Instant::now();
            let f = fit_compatible(&[l, &bo], &masters::evenly_spaced(11), tol).unwrap();
            tc += t.elapsed().as_secs_f64();
            c11 += f.segments;
            worst = f.max_error.iter().copied().fold(worst, f64::max);
            // kink at the midpoint
            let segs: Vec<Vec<kurbo::PathSeg>> =
                f.paths.iter().map(|p| p.segments().collect()).collect();
            let k = segs[0].len();
            for i in 0..k {
                let j = (i + 1) % k;
                let cub = |m: usize, x: usize| segs[m][x].to_cubic();
                let (a0, b0) = (cub(0, i), cub(0, j));
                let (ta, tb) = (a0.p3 - a0.p2, b0.p1 - b0.p0);
                if ta.hypot() == 0.0
                    || tb.hypot() == 0.0
                    || (ta.cross(tb) / (ta.hypot() * tb.hypot())).abs() > 1e-6
                    || ta.dot(tb) < 0.0
                {
                    continue;
                }
                let (a1, b1) = (cub(1, i), cub(1, j));
                let ta = 0.5 * ((a0.p3 - a0.p2) + (a1.p3 - a1.p2));
                let tb = 0.5 * ((b0.p1 - b0.p0) + (b1.p1 - b1.p0));
                let ang = (ta.cross(tb) / (ta.hypot() * tb.hypot()))
                    .asin()
                    .abs()
                    .to_degrees();
                unsafe {
                    if ang > KINK {
                        KINK = ang;
                    }
                    JOINS += 1;
                    if ang > 1.0 {
                        K1 += 1;
                    }
                    if ang > 5.0 {
                        K5 += 1;
                        eprintln!(
                            "{} kink {ang:.1} len {:.2} {:.2} / {:.2} {:.2}",
                            g.name,
                            (a0.p3 - a0.p2).hypot(),
                            (b0.p1 - b0.p0).hypot(),
                            (a1.p3 - a1.p2).hypot(),
                            (b1.p1 - b1.p0).hypot()
                        );
                    }
                }
            }
        }
        let m = sl.max(sb);
        if c11 as f64 > 1.25 * m as f64 || !only.is_empty() {
            println!(
                "{}: static {sl}/{sb} masters-only {c2} eleven {c11} ratio {:.2} worst {:.3}",
                g.name,
                c11 as f64 / m.max(1) as f64,
                worst / tol
            );
        }
        a += m;
        b += c2;
        c += c11;
        d += sl;
    }
    println!("total static max {a} (light {d}) masters-only {b} eleven {c}: {:.3}; time static-light {ts:.3}s compat11 {tc:.3}s ratio {:.2}; all {:?}; kink {} joins {} >1deg {} >5deg {}", c as f64 / a as f64, tc / ts, t0.elapsed(), unsafe { KINK }, unsafe { JOINS }, unsafe { K1 }, unsafe { K5 });
}
