//! Checking a whole scene: the pairs the broad phase keeps, in parallel, earliest contact
//! first.

use super::broad_phase::{candidate_pairs, pair_windows, Windows, PARALLEL_MIN_ROBOTS};
use super::method::Scratch;
use super::pair::{PairCheck, SharedLimit};
use super::precision::check_precision;
use super::span::PairSettings;
use super::{Method, Scene, Stats};
use crate::error::InputError;
use crate::geometry::WalkTolerances;
use rayon::prelude::*;
use serde::Serialize;

/// Scenes whose pairs have fewer merged intervals than this in all (estimated from above by
/// their sample counts) are checked on the calling thread: handing pairs to the thread pool
/// costs about as much as checking a few hundred intervals that stay apart (the 9 pairs of
/// `paper-fig12a`, 264 intervals, spent 37-40 % of their time in the hand-over).
const PARALLEL_MIN_INTERVALS: usize = 1024;

/// Scenes with fewer pairs skip the broad phase: its boxes cost about as much as checking a
/// pair that stays apart (a few disc gaps per merged interval), so it only pays with many.
const BROAD_PHASE_MIN_PAIRS: usize = 16;

/// The default time tolerance, as a fraction of the horizon's length.
pub const DEFAULT_TIME_TOL_OVER_HORIZON: f64 = 1e-6;

/// The default work budget of a pair: evaluations of η (merged interval ends, bisections
/// and looks). The pairs of the shipped scenes, corpus and generated kinds need at most a
/// few thousand; a thin tip spinning past a wall at δ·(1 + 10⁻⁹) needs about 10⁴ per turn.
pub const DEFAULT_MAX_WORK_PER_PAIR: u64 = 1_000_000;

/// How to check a scene.
///
/// ```
/// use workcell::collision::{CheckOptions, Method};
/// use workcell::motion::BoundKind;
/// // The paper's bound instead of the rigorous one, and each pair's counters.
/// let opts = CheckOptions {
///     method: Method::Adaptive(BoundKind::Paper),
///     per_pair: true,
///     ..CheckOptions::default()
/// };
/// assert_eq!(opts.time_tol_for((0.0, 8.0)), 8e-6); // 10⁻⁶ of the horizon by default
/// ```
#[derive(Clone, Copy, Debug)]
pub struct CheckOptions {
    /// δ to use instead of the scene's, in the scene's length unit.
    pub delta: Option<f64>,
    /// How each merged interval is searched (`--method`).
    pub method: Method,
    /// Absolute time tolerance of the first contact, in the scene's time unit; default
    /// 10⁻⁶ of the horizon's length.
    pub time_tol: Option<f64>,
    /// Grazing allowance, relative to δ. Certificates prove distance ≥ δ; only where that
    /// fails on an interval shorter than the time tolerance, with no witness, is
    /// δ·(1 − `grazing_tol`) accepted, and counted in [`Stats::grazing`].
    pub grazing_tol: f64,
    /// Narrow-phase tolerances and limits.
    pub walk: WalkTolerances,
    /// Also report each pair's counters ([`CheckReport::pair_stats`]).
    pub per_pair: bool,
    /// Work budget of each pair, in evaluations of η ([`DEFAULT_MAX_WORK_PER_PAIR`]). A pair
    /// that spends it before a proof or a witness stops there, and the report says so
    /// ([`CheckReport::budget_exhausted`]): never free.
    pub max_work_per_pair: u64,
    /// Count the work through the scene's first event exactly (a record per merged
    /// interval examined), as reports show it. Off, the counters count all the work the
    /// pairs did, but grazes and unresolved intervals, which certify the report, still count
    /// through the first event only: for checks whose counters nobody reads.
    pub counters: bool,
}

impl CheckOptions {
    /// The absolute time tolerance used on a scene of this horizon: `time_tol`, else
    /// [`DEFAULT_TIME_TOL_OVER_HORIZON`] of its length.
    ///
    /// ```
    /// use workcell::collision::{CheckOptions, DEFAULT_TIME_TOL_OVER_HORIZON};
    /// let default = CheckOptions::default();
    /// assert_eq!(default.time_tol_for((10.0, 30.0)), DEFAULT_TIME_TOL_OVER_HORIZON * 20.0);
    /// let given = CheckOptions { time_tol: Some(1e-6), ..default };
    /// assert_eq!(given.time_tol_for((10.0, 30.0)), 1e-6);
    /// ```
    pub fn time_tol_for(&self, (start, end): (f64, f64)) -> f64 {
        self.time_tol
            .unwrap_or(DEFAULT_TIME_TOL_OVER_HORIZON * (end - start))
    }
}

impl Default for CheckOptions {
    fn default() -> Self {
        CheckOptions {
            delta: None,
            method: Method::DEFAULT,
            time_tol: None,
            grazing_tol: 1e-4,
            walk: WalkTolerances::default(),
            per_pair: false,
            max_work_per_pair: DEFAULT_MAX_WORK_PER_PAIR,
            counters: true,
        }
    }
}

/// The first contact of a scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contact {
    /// A time at which the two bodies are closer than δ, and no more than the time
    /// tolerance after the earliest such time of the scene.
    pub time: f64,
    /// The pair: a robot and an obstacle name the robot first.
    pub bodies: [String; 2],
    /// Exact distance at `time` (below δ; 0 on overlap).
    pub distance: f64,
    /// 1-based index of the pair's merged interval that holds `time`.
    pub interval: usize,
    /// For a body given by `parts`, the index of its part in contact (contract section 5;
    /// `None` for a body given by `shape` or `outline`); left out when neither body has
    /// `parts`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parts: Option<[Option<usize>; 2]>,
    /// For an arm, the 0-based index of its link in contact (contract section 6; `None` for
    /// a body that is not an arm); left out when neither body is an arm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub links: Option<[Option<usize>; 2]>,
}

/// Where a pair spent its work budget before a proof or a witness.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BudgetExhausted {
    /// End of the prefix of the horizon certified for that pair; beyond it nothing is known.
    pub time: f64,
    /// The pair, robot first.
    pub bodies: [String; 2],
    /// The budget spent, in evaluations of η.
    pub work: u64,
}

/// Result of a check, serialised as the scene contract's result (section 2) plus extras.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CheckReport {
    /// Whether any pair comes closer than δ.
    pub collision: bool,
    /// The earliest contact, if any.
    pub first_contact: Option<Contact>,
    /// End of the prefix of the horizon certified free (with a method that proves nothing,
    /// the last look found free before the contact).
    pub safe_until: f64,
    /// Whether the whole report is proven. False with a method that proves nothing
    /// ([`Method::proves_free`]), and when some interval examined only grazes δ or could not
    /// be resolved (see [`Stats`]): then a verdict of free, or the prefix before
    /// `safe_until`, holds only down to δ·(1 − grazing_tol). A reported contact itself is
    /// always real (it has a witness).
    pub certified: bool,
    /// When a pair spent its work budget ([`CheckOptions::max_work_per_pair`]) before any
    /// contact: where. `collision` is then false, `certified` false and `safe_until` at most
    /// that time: the scene is neither proven free nor found colliding after it.
    pub budget_exhausted: Option<BudgetExhausted>,
    /// Counters, summed over pairs; independent of the number of threads.
    pub stats: Stats,
    /// First and last sample time of any robot.
    pub horizon: [f64; 2],
    /// δ used.
    pub delta: f64,
    /// Absolute time tolerance used.
    pub time_tol: f64,
    /// Number of body pairs checked by the narrow (adaptive) stage.
    pub pairs: usize,
    /// Number of body pairs the broad phase proved δ apart over the whole horizon, and
    /// therefore not checked; `pairs + pairs_pruned` is the number of robot-robot and
    /// robot-obstacle pairs of the scene.
    pub pairs_pruned: usize,
    /// With [`CheckOptions::per_pair`]: each checked pair's share of `stats`, in report order.
    /// Pruned pairs do no work and are not listed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pair_stats: Option<Vec<PairStats>>,
}

/// One pair's counters.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PairStats {
    /// The pair, robot first.
    pub bodies: [String; 2],
    /// Its merged intervals in all (the paper's "71 intervals").
    pub merged_intervals: usize,
    /// Its share of the report's counters.
    pub stats: Stats,
}

/// Checks every robot-robot and robot-obstacle pair of `scene` over its horizon.
///
/// With 16 pairs or more, the broad phase ([`super::candidate_pairs`]) first drops the pairs
/// whose swept bounding boxes stay δ apart; only the others are checked. A robot with a long
/// trajectory is checked against each obstacle only where its boxes, chunk by chunk of its
/// samples, meet the obstacle's (elsewhere the boxes prove the pair δ apart). Dropped pairs could
/// never give a contact, so the verdict, the first contact and `safe_until` are those of
/// checking all pairs; the counters, and so `certified`, only cover the pairs checked (a
/// pruned pair's distance is proven ≥ δ, grazes included).
///
/// Guarantee (rigorous bound, a scene that passes [`super::check_precision`] at the δ
/// used): when `collision` is false, no pair comes closer than δ at any time of the horizon,
/// except within [`Stats::grazing`] intervals, each shorter than the time tolerance, where
/// the distance stays above δ·(1 − grazing_tol) (`certified` is then false). When true, the
/// pair named is closer than δ at `first_contact.time` (an exact distance), and the same
/// holds before `safe_until`, which is within the time tolerance before it. The result,
/// counters included, does not depend on the number of threads.
///
/// # Panics
///
/// When [`validate`] refuses the arguments (a δ that is not a positive number, say): such a
/// check would never end or would prove nothing. [`try_check`] returns that error instead.
///
/// # Examples
///
/// ```
/// use workcell::collision::{check, Body, CheckOptions, Scene};
/// use workcell::geometry::ConvexPolygon;
/// use workcell::motion::{Pose, Trajectory};
/// // Two robots passing 2 apart (centre to centre; 1 between their sides).
/// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
/// let lane = |y: f64| Trajectory::from_poses([(0.0, Pose::new(0.0, y, 0.0)), (5.0, Pose::new(5.0, y, 0.0))]);
/// let scene = Scene::with_bodies(0.1, [
///     Body::robot("low", square.clone(), lane(0.0)?),
///     Body::robot("high", square, lane(2.0)?),
/// ])?;
/// let report = check(&scene, &CheckOptions::default());
/// assert!(report.verdict().is_certified_free());
/// assert_eq!((report.pairs, report.horizon), (1, [0.0, 5.0]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check(scene: &Scene, opts: &CheckOptions) -> CheckReport {
    check_known(scene, opts, &[])
}

/// [`check`] of a scene some of whose pairs an earlier check proved δ apart up to a time:
/// bodies `i` and `j` are known δ apart before `min(known[i], known[j])` (a body not listed
/// is known nowhere), and the merged intervals that end by then are skipped, as the broad
/// phase skips those its boxes prove free (the first interval examined starts from a fresh
/// evaluation). When the knowledge is true, the verdict, the first contact and `safe_until`
/// are those of [`check`], and the counters count only the intervals examined; what is known
/// is the caller's to prove, and is not checked again.
///
/// ```
/// use workcell::collision::{check, check_known, Body, CheckOptions, Scene};
/// use workcell::geometry::ConvexPolygon;
/// use workcell::motion::{Pose, Trajectory};
/// // A unit square driving at 1 into one standing 6 ahead: they meet near t = 5.
/// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
/// let drive = Trajectory::from_poses((0..=10).map(|t| (t as f64, Pose::new(t as f64, 0.0, 0.0))))?;
/// let stand = Trajectory::from_poses([(0.0, Pose::new(6.0, 0.0, 0.0)), (10.0, Pose::new(6.0, 0.0, 0.0))])?;
/// let scene = Scene::with_bodies(0.1, [
///     Body::robot("driver", square.clone(), drive),
///     Body::robot("wall", square, stand),
/// ])?;
/// let opts = CheckOptions::default();
/// let full = check(&scene, &opts);
/// // Known apart up to t = 3 (true): the same contact, fewer intervals searched.
/// let known = check_known(&scene, &opts, &[3.0, 3.0]);
/// assert_eq!((known.first_contact, known.safe_until), (full.first_contact.clone(), full.safe_until));
/// assert!(known.stats.intervals < full.stats.intervals);
/// // Told they are apart up to t = 6 (false), the check takes it: the contact found is later.
/// let told = check_known(&scene, &opts, &[6.0, 6.0]);
/// assert!(told.first_contact.unwrap().time > full.first_contact.unwrap().time);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check_known(scene: &Scene, opts: &CheckOptions, known: &[f64]) -> CheckReport {
    if let Err(e) = validate(scene, opts) {
        panic!("collision::check: {e}");
    }
    if scene.robot_count() >= PARALLEL_MIN_ROBOTS {
        // The broad phase goes to the thread pool twice and the pairs once more: from a
        // thread outside the pool, hand the whole check over once instead.
        rayon::scope(|_| check_in_pool(scene, opts, known))
    } else {
        check_in_pool(scene, opts, known)
    }
}

/// [`check`] for a scene and options not validated yet: refuses, as `workcell check` does,
/// what [`validate`] refuses and scenes that f64 cannot check at their δ
/// ([`super::check_precision`]). The errors name the field and no file.
///
/// ```
/// use workcell::collision::{try_check, CheckOptions, Scene};
/// let scene = Scene::new(0.01)?;
/// let opts = CheckOptions { delta: Some(f64::NAN), ..CheckOptions::default() };
/// let e = try_check(&scene, &opts).unwrap_err();
/// assert_eq!(e.to_string(), "field `delta`: must be a positive number, got NaN");
/// // An empty scene is free: there is no pair.
/// assert!(try_check(&scene, &CheckOptions::default())?.verdict().is_certified_free());
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn try_check(scene: &Scene, opts: &CheckOptions) -> Result<CheckReport, InputError> {
    validate(scene, opts)?;
    check_precision(
        scene,
        opts.delta.unwrap_or(scene.delta),
        std::path::Path::new(""),
    )?;
    Ok(check(scene, opts))
}

/// Refuses arguments that a check could not honour: a δ (the options' or else the scene's)
/// or a time tolerance that is not a positive number, a grazing allowance outside [0, 1), and
/// a `sampled` step that is not positive, finer than f64 resolves the horizon's times, or
/// so fine that the looks would exceed [`super::MAX_SAMPLED_LOOKS`] per pair. Fields are
/// named after [`CheckOptions`] (`delta` for the scene's δ); the error names no file.
///
/// ```
/// use workcell::collision::{validate, CheckOptions, Scene};
/// let scene = Scene::new(0.01)?;
/// let opts = CheckOptions { grazing_tol: 1.0, ..CheckOptions::default() };
/// assert_eq!(validate(&scene, &opts).unwrap_err().field, "grazing_tol");
/// assert!(validate(&scene, &CheckOptions::default()).is_ok());
/// # Ok::<(), workcell::cell::InputError>(())
/// ```
pub fn validate(scene: &Scene, opts: &CheckOptions) -> Result<(), InputError> {
    let refuse = |field: &str, reason: String| {
        Err(InputError::new(
            std::path::Path::new(""),
            None,
            field,
            reason,
        ))
    };
    let positive = |v: f64| v.is_finite() && v > 0.0;
    super::check_delta(opts.delta.unwrap_or(scene.delta))?;
    if let Some(tol) = opts.time_tol.filter(|&t| !positive(t)) {
        return refuse("time_tol", format!("must be a positive number, got {tol}"));
    }
    if !(0.0..1.0).contains(&opts.grazing_tol) {
        let reason = format!("must lie in [0, 1), got {}", opts.grazing_tol);
        return refuse("grazing_tol", reason);
    }
    if let Method::Sampled { step } = opts.method {
        if let Some(why) = super::sampled::step_problem(step, scene.horizon()) {
            return refuse("method", why);
        }
    }
    Ok(())
}

fn check_in_pool(scene: &Scene, opts: &CheckOptions, known: &[f64]) -> CheckReport {
    let horizon = scene.horizon();
    let delta = opts.delta.unwrap_or(scene.delta);
    let time_tol = opts.time_tol_for(horizon);
    let settings = PairSettings {
        delta,
        grazing_tol: opts.grazing_tol * delta,
        time_tol,
        start: horizon.0,
        walk: opts.walk,
        max_work: opts.max_work_per_pair,
        counters: opts.counters,
    };
    let all_pairs = scene.pair_count();
    let pairs = if all_pairs < BROAD_PHASE_MIN_PAIRS {
        scene.pairs()
    } else {
        candidate_pairs(scene, delta)
    };
    // A robot with a long trajectory meets most obstacles only now and then: each such
    // pair is checked in its windows, and dropped when it has none; a pair known apart up
    // to a time, from there on only.
    let from = |(i, j): (usize, usize)| {
        let at = |k: usize| known.get(k).copied().unwrap_or(f64::NEG_INFINITY);
        at(i).min(at(j))
    };
    let (pairs, windows): (Vec<_>, Vec<_>) = pairs
        .iter()
        .copied()
        .zip(pair_windows(scene, &pairs, delta))
        .map(|(p, w)| match from(p) {
            t if t > horizon.0 => (p, Some(after(w, t))),
            _ => (p, w),
        })
        .filter(|(_, w)| w.as_ref().is_none_or(|w| !w.is_empty()))
        .unzip();
    // The pairs known least go first: a change made to a body is where the first contact
    // most often is, and a contact found stops the others sooner.
    let latest = pairs
        .iter()
        .map(|&p| from(p))
        .fold(f64::NEG_INFINITY, f64::max);
    let first: Vec<bool> = pairs.iter().map(|&p| from(p) < latest).collect();
    let checks = run_pairs(scene, opts, (&pairs, &first), windows, &settings);
    report(scene, opts, &settings, (all_pairs, &pairs), &checks)
}

/// Windows `w` (`None`: the whole horizon) from time `t` on.
fn after(w: Option<Windows>, t: f64) -> Windows {
    match w {
        None => vec![(t, f64::INFINITY)],
        Some(w) => (w.into_iter())
            .filter(|&(_, end)| end > t)
            .map(|(start, end)| (start.max(t), end))
            .collect(),
    }
}

/// Each pair checked through the horizon, those marked `first` before the others, with the
/// limit they found: on the pool when the work is worth it. The checks come in the order
/// of `pairs`.
fn run_pairs<'s>(
    scene: &'s Scene,
    opts: &CheckOptions,
    (pairs, first): (&[(usize, usize)], &[bool]),
    windows: Vec<Option<Windows>>,
    settings: &PairSettings,
) -> Vec<PairCheck<'s>> {
    let horizon = scene.horizon();
    let limit = SharedLimit::new();
    // Every pair is evaluated at the start before any runs on: a contact there stops all
    // of them at their first interval.
    let start = |(&(i, j), windows): (&(usize, usize), Option<Windows>)| {
        PairCheck::start(
            &scene.bodies[i],
            &scene.bodies[j],
            horizon,
            settings,
            &limit,
            windows,
        )
    };
    let finish = |scratch: &mut Scratch, pair: &mut PairCheck| {
        pair.finish(opts.method, settings, &limit, scratch);
    };
    // Decided by the work, not the number of pairs: many short pairs are quicker on one
    // thread, a few long ones are not.
    let work: usize = pairs
        .iter()
        .map(|&(i, j)| sample_count(&scene.bodies[i]) + sample_count(&scene.bodies[j]) + 1)
        .sum();
    // Each pair's state stays where it started until the report is made.
    let parallel = pairs.len() > 1 && work >= PARALLEL_MIN_INTERVALS;
    let mut checks: Vec<PairCheck> = match parallel {
        true => pairs.par_iter().zip(windows).map(start).collect(),
        false => pairs.iter().zip(windows).map(start).collect(),
    };
    let (mut lead, mut rest): (Vec<_>, Vec<_>) =
        (checks.iter_mut().zip(first)).partition(|(_, &f)| f);
    for phase in [&mut lead, &mut rest] {
        if parallel {
            (phase.par_iter_mut()).for_each_init(Scratch::default, |s, (p, _)| finish(s, p));
        } else {
            let mut scratch = Scratch::default();
            phase.iter_mut().for_each(|(p, _)| finish(&mut scratch, p));
        }
    }
    checks
}

/// The scene's report from its pairs' checks: the earliest contact or budget run out, and
/// the statistics through it.
fn report(
    scene: &Scene,
    opts: &CheckOptions,
    settings: &PairSettings,
    (all_pairs, pairs): (usize, &[(usize, usize)]),
    checks: &[PairCheck],
) -> CheckReport {
    let (horizon, delta, time_tol) = (scene.horizon(), settings.delta, settings.time_tol);
    let outcomes = || checks.iter().map(PairCheck::outcome);
    // Earliest contact; ties go to the first pair in report order.
    let contact = outcomes()
        .zip(pairs)
        .filter_map(|(o, p)| o.contact.map(|c| (c, p)))
        .min_by(|x, y| x.0.time.total_cmp(&y.0.time));
    // Earliest budget run out, which hides whatever comes after it; a contact at the same
    // time wins.
    let exhausted = outcomes()
        .zip(pairs)
        .filter(|(o, _)| o.out_of_work)
        .map(|(o, p)| (o.safe_until, p))
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .filter(|&(t, _)| contact.is_none_or(|(c, _)| t < c.time));
    let first = contact.filter(|_| exhausted.is_none());
    let through = match (first, exhausted) {
        (Some((c, _)), _) => c.time,
        (None, Some((t, _))) => t,
        (None, None) => f64::INFINITY,
    };
    let names =
        |(i, j): (usize, usize)| [scene.bodies[i].name.clone(), scene.bodies[j].name.clone()];
    let mut stats = Stats::default();
    for c in checks {
        stats += c.stats_through(through);
    }
    let pair_stats = opts.per_pair.then(|| {
        checks
            .iter()
            .zip(pairs)
            .map(|(c, &p)| PairStats {
                bodies: names(p),
                merged_intervals: c.merged_intervals(),
                stats: c.stats_through(through),
            })
            .collect()
    });
    let safe_until = outcomes().map(|o| o.safe_until).fold(horizon.1, f64::min);
    CheckReport {
        collision: first.is_some(),
        certified: opts.method.proves_free()
            && stats.grazing == 0
            && stats.unresolved == 0
            && exhausted.is_none(),
        budget_exhausted: exhausted.map(|(time, &p)| BudgetExhausted {
            time,
            bodies: names(p),
            work: opts.max_work_per_pair,
        }),
        first_contact: first.map(|(c, &(i, j))| Contact {
            time: c.time,
            bodies: names((i, j)),
            distance: c.distance,
            interval: c.interval,
            parts: contact_parts(&scene.bodies[i], &scene.bodies[j], c.parts),
            links: contact_links(&scene.bodies[i], &scene.bodies[j]),
        }),
        safe_until,
        stats,
        horizon: [horizon.0, horizon.1],
        delta,
        time_tol,
        pairs: pairs.len(),
        pairs_pruned: all_pairs - pairs.len(),
        pair_stats,
    }
}

/// The links in contact as the report names them: the link's index for an arm, none for a
/// body that is not one; left out when neither is an arm.
fn contact_links(a: &super::Body, b: &super::Body) -> Option<[Option<usize>; 2]> {
    let links = [a.link(), b.link()];
    links.iter().any(Option::is_some).then_some(links)
}

/// The parts in contact as the report names them: an index for a body given by `parts`,
/// none for one given by `shape` or `outline` (its parts are the project's, not the user's).
fn contact_parts(
    a: &super::Body,
    b: &super::Body,
    parts: Option<(usize, usize)>,
) -> Option<[Option<usize>; 2]> {
    let listed = |body: &super::Body| body.parts.as_ref().is_some_and(|p| p.outline().is_none());
    let (i, j) = parts?;
    (listed(a) || listed(b)).then(|| [listed(a).then_some(i), listed(b).then_some(j)])
}

/// The number of a body's samples (0 for an obstacle): with the other body's, a bound on the
/// merged intervals of a pair.
fn sample_count(body: &super::Body) -> usize {
    match &body.motion {
        crate::motion::Motion::Sampled(tr) => tr.samples().len(),
        crate::motion::Motion::Link(l) => l.arm.samples().len(),
        crate::motion::Motion::Fixed(_) => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pair known apart up to a time keeps only what of its windows lies after it.
    #[test]
    fn windows_after_a_time_keep_what_lies_after_it() {
        assert_eq!(after(None, 2.0), vec![(2.0, f64::INFINITY)]);
        let w = vec![(0.0, 1.0), (1.5, 3.0), (4.0, 5.0)];
        assert_eq!(after(Some(w.clone()), 2.0), vec![(2.0, 3.0), (4.0, 5.0)]);
        // A window ending at the time holds nothing after it.
        assert_eq!(after(Some(w.clone()), 3.0), vec![(4.0, 5.0)]);
        assert_eq!(after(Some(w), 6.0), vec![]);
    }
}
