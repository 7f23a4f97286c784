//! `solve --trace`: the anytime curve, one CSV line per better plan or schedule found.
//!
//! Columns: `seconds` since the solve started, `stage` (`sequencing`: a plan of the
//! sequencer, its makespan on the travel times it knows, unchecked; `certified`: a schedule
//! the checker certified collision-free), `makespan`, `certified` (`true`/`false`),
//! `lower_bound` (of the collision-blind makespan, see
//! [`Prepared::makespan_lower_bound`](workcell::wcp::Prepared::makespan_lower_bound); empty
//! before it is known). Each stage's makespans decrease down the file; the last
//! `certified` line is the answer of a solve that found a collision-free schedule.

use std::fmt::Write;
use std::sync::Mutex;
use std::time::Instant;

/// The header line of the CSV.
pub const HEADER: &str = "seconds,stage,makespan,certified,lower_bound";

/// The rows so far, and the best of each stage.
pub struct Trace {
    start: Instant,
    state: Mutex<State>,
}

struct State {
    rows: Vec<Row>,
    best_plan: f64,
    best_certified: f64,
    lower_bound: Option<f64>,
}

struct Row {
    seconds: f64,
    certified: bool,
    makespan: f64,
    lower_bound: Option<f64>,
}

impl Trace {
    /// An empty trace, its clock started.
    pub fn new(start: Instant) -> Trace {
        Trace {
            start,
            state: Mutex::new(State {
                rows: Vec::new(),
                best_plan: f64::INFINITY,
                best_certified: f64::INFINITY,
                lower_bound: None,
            }),
        }
    }

    /// The lower bound of the rows from now on.
    pub fn lower_bound(&self, bound: f64) {
        self.state.lock().expect("no panic while held").lower_bound = Some(bound);
    }

    /// A plan (`certified` false) or a certified schedule of this makespan: a row if it is
    /// the best of its stage so far.
    pub fn found(&self, makespan: f64, certified: bool) {
        let mut s = self.state.lock().expect("no panic while held");
        let best = match certified {
            true => &mut s.best_certified,
            false => &mut s.best_plan,
        };
        // NaN is never better.
        if makespan.partial_cmp(best) != Some(std::cmp::Ordering::Less) {
            return;
        }
        *best = makespan;
        let row = Row {
            seconds: self.start.elapsed().as_secs_f64(),
            certified,
            makespan,
            lower_bound: s.lower_bound,
        };
        s.rows.push(row);
    }

    /// The CSV text.
    pub fn csv(&self) -> String {
        let s = self.state.lock().expect("no panic while held");
        let mut out = format!("{HEADER}\n");
        for r in &s.rows {
            let stage = if r.certified {
                "certified"
            } else {
                "sequencing"
            };
            let bound = r.lower_bound.map(|b| b.to_string()).unwrap_or_default();
            let _ = writeln!(
                out,
                "{:.6},{stage},{},{},{bound}",
                r.seconds, r.makespan, r.certified
            );
        }
        out
    }
}
