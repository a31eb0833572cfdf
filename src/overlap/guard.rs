//! linesweeper's sweep run so that its panics cannot take the program down.
//!
//! linesweeper 0.5 can panic on near-degenerate input: an `unwrap` in its sweep line's order
//! lookup (`curve/mod.rs`, `CurveOrder::order_at`) fails when two curves' comparison does
//! not reach the sweep's height. Found on stroke outlines of icon sets (heroicons' `bold`,
//! tabler's and lucide's outline icons), whose vertices lie 2e-5 units apart where a stroke
//! turns on itself. Such vertices are closer than the sweep's accuracy `eps`, so merging
//! them costs nothing the sweep does not already allow: on a panic the sweep runs once more
//! on the input with every coordinate snapped to a grid of `eps` (which moves no point by
//! more than `eps`), and when that panics too the caller gets `None` and keeps its input.
//!
//! Why by hand: the panic is linesweeper's, and no release fixes it (0.5.0 is the newest);
//! `catch_unwind` is the only way to keep a user's import or build alive. The panic hook
//! stays quiet while a sweep is guarded, so a recovered panic prints nothing; any other
//! panic, on any thread, is reported as before.

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

use kurbo::{BezPath, PathEl, Point};

thread_local! {
    /// Whether this thread is inside [`guarded`]: its panics are expected and caught.
    static GUARDED: Cell<bool> = const { Cell::new(false) };
}

static QUIET_HOOK: Once = Once::new();

/// `sweep(None)`, or when it panics `sweep(Some(eps))` (the caller snaps its inputs to that
/// grid with [`snapped`]); `None` when both panic.
pub fn guarded<R>(eps: f64, sweep: impl Fn(Option<f64>) -> R) -> Option<R> {
    QUIET_HOOK.call_once(|| {
        let report = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !GUARDED.with(Cell::get) {
                report(info);
            }
        }));
    });
    let outer = GUARDED.with(|g| g.replace(true));
    // AssertUnwindSafe: the sweep reads its inputs and builds its own state, which is
    // dropped with the panic; nothing shared is left half-written.
    let result = panic::catch_unwind(AssertUnwindSafe(|| sweep(None)))
        .or_else(|_| panic::catch_unwind(AssertUnwindSafe(|| sweep(Some(eps)))))
        .ok();
    GUARDED.with(|g| g.set(outer));
    result
}

/// `path` with every coordinate rounded to the nearest multiple of `grid`.
pub fn snapped(path: &BezPath, grid: f64) -> BezPath {
    let snap = |p: Point| Point::new((p.x / grid).round() * grid, (p.y / grid).round() * grid);
    path.iter()
        .map(|el| match el {
            PathEl::MoveTo(p) => PathEl::MoveTo(snap(p)),
            PathEl::LineTo(p) => PathEl::LineTo(snap(p)),
            PathEl::QuadTo(a, p) => PathEl::QuadTo(snap(a), snap(p)),
            PathEl::CurveTo(a, b, p) => PathEl::CurveTo(snap(a), snap(b), snap(p)),
            PathEl::ClosePath => PathEl::ClosePath,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panicking_sweep_is_run_again_on_the_grid() {
        let tries = Cell::new(Vec::new());
        let result = guarded(0.25, |grid| {
            let mut seen = tries.take();
            seen.push(grid);
            tries.set(seen);
            if grid.is_none() {
                panic!("first try");
            }
            7
        });
        assert_eq!(result, Some(7));
        assert_eq!(tries.take(), vec![None, Some(0.25)]);
        assert_eq!(guarded(0.25, |_| -> u8 { panic!("always") }), None);
        assert!(
            !GUARDED.with(Cell::get),
            "the guard is lifted after the sweep"
        );
    }

    #[test]
    fn snapping_moves_each_point_to_the_nearest_grid_point() {
        let mut path = BezPath::new();
        path.move_to((0.26, -0.13));
        path.quad_to((1.13, 0.37), (2.0, -0.38));
        path.close_path();
        let got = snapped(&path, 0.25);
        assert_eq!(got.to_svg(), "M0.25,-0.25 Q1.25,0.25 2,-0.5 Z");
    }
}
