//! Batch evaluation allocates nothing once the curves are lowered: a counting global
//! allocator (implementing `GlobalAlloc` needs `unsafe`) counts the allocations of the
//! evaluating thread.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use glam::DVec3;
use splinescope_core::geom::batch::CurveSampler;

struct Counting;

thread_local! {
    /// Whether this thread's allocations are counted (the harness's threads allocate too).
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    if COUNTING.with(Cell::get) {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator; the counter only
// observes (const-initialised thread locals do not allocate).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn batch_evaluation_allocates_nothing_once_the_curves_are_lowered() {
    let scene = splinescope_scene::format::gallery::gallery();
    let samplers: Vec<CurveSampler> = scene
        .curves
        .iter()
        .map(|c| CurveSampler::new(&c.curve))
        .collect();
    let ts: Vec<f64> = (0..500).map(|k| f64::from(k) / 499.0).collect();
    let mut out = vec![DVec3::ZERO; 500];
    // The counter itself is seen to count.
    COUNTING.with(|c| c.set(true));
    drop(std::hint::black_box(vec![0u8; 8]));
    COUNTING.with(|c| c.set(false));
    assert_eq!(ALLOCATIONS.with(Cell::get), 1, "the counter counts");
    ALLOCATIONS.with(|n| n.set(0));
    COUNTING.with(|c| c.set(true));
    for s in &samplers {
        let (a, b) = s.domain();
        s.eval_into(&ts, &mut out);
        s.eval_into(&[b, a, 0.5 * (a + b)], &mut out[..3]);
        s.sample_uniform_into(500, &mut out);
    }
    COUNTING.with(|c| c.set(false));
    assert_eq!(ALLOCATIONS.with(Cell::get), 0, "evaluation allocated");
}
