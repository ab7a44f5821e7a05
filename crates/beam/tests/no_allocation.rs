//! The time step allocates no memory once its workspace exists: a counting global allocator
//! (counting only the allocations of the test's own thread) over steps of the Exudyn
//! comparison's step-load transient (ANCF, symmetric LDLᵀ path; corotational, pivoting LU
//! path) and of the linear model.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use flexrig_beam::*;

struct Counting;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            COUNT.with(|c| c.set(c.get() + 1));
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            COUNT.with(|c| c.set(c.get() + 1));
        }
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations(f: impl FnOnce()) -> usize {
    COUNT.with(|c| c.set(0));
    COUNTING.with(|c| c.set(true));
    f();
    COUNTING.with(|c| c.set(false));
    COUNT.with(Cell::get)
}

#[test]
fn generalized_alpha_steps_allocate_nothing() {
    // the counter itself works
    assert!(allocations(|| drop(std::hint::black_box(vec![1.0f64; 8]))) >= 1);
    let ga = GeneralizedAlpha::new(0.9).unwrap();
    for kin in [
        Kinematics::Ancf,
        Kinematics::Corotational,
        Kinematics::Linear,
    ] {
        let (model, loads) = canonical::polypropylene_cantilever(16, kin).unwrap();
        let mut s = State::at_rest(&model, &loads).unwrap();
        let mut ws = Workspace::new(&model);
        // the first steps settle the predictor (the step load makes the first one restart)
        for _ in 0..20 {
            ga.step(&model, &mut s, &mut ws, 1e-3, &loads).unwrap();
        }
        let mut rejected = 0;
        let n = allocations(|| {
            for _ in 0..200 {
                let r = ga.step(&model, &mut s, &mut ws, 1e-3, &loads).unwrap();
                rejected += r.rejected;
            }
        });
        assert_eq!(
            rejected, 0,
            "{kin:?}: no step restarted in the counted range"
        );
        assert_eq!(n, 0, "{kin:?}: {n} allocations in 200 steps");
    }
}
