//! A sequences file costs about its own size to read, not a tree of JSON maps (issue 13,
//! item 11: a 96 MB result with 2·10⁶ waits took 1.7 GB). Allocations are counted by this
//! test binary's allocator, so the measure is exact and the same on every run.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use workcell::cell::{load_cell, parse_sequences};

/// The system allocator, counting the bytes in use and their peak.
struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = IN_USE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        IN_USE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn a_result_with_many_waits_is_read_in_about_its_own_size() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cells/feedback-cell.json");
    let cell = load_cell(&path).unwrap().cell;
    const WAITS: usize = 200_000;
    let wait = r#"{"robot": "R2", "before_move": 0, "duration": 1e-7}"#;
    let text = format!(
        r#"{{"makespan": 20, "sequences": {{"R1": ["weld-2", "weld-3", "weld-1"], "R2": ["weld-4"]}},
            "waits": [{}]}}"#,
        vec![wait; WAITS].join(", ")
    );
    let before = IN_USE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let sequences = parse_sequences(&text, Path::new("result.json"), &cell).unwrap();
    let peak = PEAK.load(Ordering::Relaxed) - before;
    assert_eq!(sequences.waits.len(), WAITS);
    // The waits themselves take 24 bytes each, about half the text; a JSON tree took 18×.
    assert!(
        peak <= 2 * text.len(),
        "reading {} bytes took up to {peak} bytes",
        text.len()
    );
}
