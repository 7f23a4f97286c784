//! Memory that must stay in proportion to the input: a sequences file costs about its own
//! size to read, not a tree of JSON maps (a 96 MB result with 2·10⁶ waits took 1.7 GB), and
//! the check of a long trajectory among many obstacles costs in proportion to its samples,
//! not samples × obstacles. Allocations are counted by this test binary's allocator, so the
//! measure is exact; the tests take turns (`ONE_AT_A_TIME`), so that each counts its own.

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

/// Held by each test while it counts.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[test]
fn a_result_with_many_waits_is_read_in_about_its_own_size() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
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

/// A robot sweeping 20,000 samples back and forth across a field of 200 posts: each post is
/// near its path only now and then. The check's memory is a few times the trajectory's, as
/// it was when every robot-post pair kept a record of every interval of the horizon (then
/// 200 × 20,000 records of 80 bytes, 320 MB).
#[test]
fn checking_a_long_trajectory_among_many_obstacles_costs_memory_in_proportion() {
    use workcell::collision::{check, Body, CheckOptions, Scene};
    use workcell::geometry::{ConvexPolygon, Vec2};
    use workcell::motion::{Pose, Trajectory};
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    const SAMPLES: usize = 20_000;
    // Rows 4 apart, 100 long, walked at 1 per unit of time, one sample per 0.5.
    let poses = (0..SAMPLES).map(|k| {
        let s = k as f64 * 0.5;
        let (row, along) = ((s / 100.0).floor(), s % 100.0);
        let x = if (row as u64).is_multiple_of(2) {
            along
        } else {
            100.0 - along
        };
        (s, Pose::new(x, 4.0 * (row % 10.0), 0.0))
    });
    let robot = ConvexPolygon::rectangle(0.6, 0.6).unwrap();
    let mut bodies = vec![Body::robot(
        "R",
        robot,
        Trajectory::from_poses(poses).unwrap(),
    )];
    for k in 0..200 {
        // Posts between the rows, 1.5 from each path.
        let (x, y) = ((k % 20) as f64 * 5.0 + 2.0, (k / 20) as f64 * 4.0 + 2.0);
        let post = ConvexPolygon::rectangle(0.4, 0.4).unwrap();
        bodies.push(Body::obstacle(
            format!("post-{k}"),
            &post.translated(&Vec2::new(-x, -y)),
        ));
    }
    let scene = Scene::with_bodies(0.01, bodies).unwrap();
    let trajectory_bytes = SAMPLES * 7 * 8;
    let before = IN_USE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let report = check(&scene, &CheckOptions::default());
    let peak = PEAK.load(Ordering::Relaxed) - before;
    assert!(report.verdict().is_certified_free(), "{report:?}");
    assert!(
        peak <= 4 * trajectory_bytes,
        "checking took up to {peak} bytes for a trajectory of {trajectory_bytes}"
    );
}
