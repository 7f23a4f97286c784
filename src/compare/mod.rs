//! Speed against accuracy: every checking method on the same scenes, judged against a
//! reference (`workcell compare`).
//!
//! The reference is the default method at a time tolerance of [`REFERENCE_TIME_TOL`] of the
//! horizon. Against it, per method: the median wall time of a whole-scene check, the
//! collisions missed, the collisions invented (a contact reported where the reference
//! certifies the distance ≥ δ: on a free scene, or before its certified prefix ends), and
//! the largest error of the first contact time. With the feature `parry-peer`, parry2d-f64's
//! nonlinear shape cast runs as the method `parry` and cross-checks the reference.

use crate::cell::InputError;
use crate::collision::{check, validate, CheckOptions, CheckReport, Method, Scene};
use serde::Serialize;
use std::fmt;
use std::str::FromStr;
use std::time::{Duration, Instant};

/// Time tolerance of the reference, relative to the horizon's length.
pub const REFERENCE_TIME_TOL: f64 = 1e-9;

/// A reported contact earlier than the reference's certified prefix by more than this
/// fraction of the horizon is invented; the default time tolerance of a check.
pub const INVENTED_SLACK: f64 = 1e-6;

/// Each scene is checked repeatedly until this much time has passed (at least once), and the
/// mean is its time: short checks are otherwise below the clock's resolution.
const MIN_TIMED: Duration = Duration::from_millis(2);

/// A contender: one of our methods, or the parry peer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Contender {
    /// Our checker with this method.
    Ours(Method),
    /// parry2d-f64's `cast_shapes_nonlinear` on each merged interval (feature `parry-peer`).
    Parry,
}

impl fmt::Display for Contender {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Contender::Ours(m) => m.fmt(f),
            Contender::Parry => f.write_str("parry"),
        }
    }
}

impl FromStr for Contender {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "parry" if cfg!(feature = "parry-peer") => Ok(Contender::Parry),
            "parry" => Err(
                "the parry peer is not built in: build with `--features parry-peer`".to_string(),
            ),
            // The methods' own list does not know the peer.
            _ => s.parse().map(Contender::Ours).map_err(|e: String| {
                let parry = if cfg!(feature = "parry-peer") {
                    "parry"
                } else {
                    "parry (with the feature parry-peer)"
                };
                match e.strip_suffix("sampled:STEP or advance") {
                    Some(head) => format!("{head}sampled:STEP, advance or {parry}"),
                    None => e,
                }
            }),
        }
    }
}

/// The contenders compared by default: every method, sampling at four steps, and parry when
/// it is built in.
///
/// ```
/// use workcell::collision::Method;
/// use workcell::compare::{default_contenders, Contender};
/// let all = default_contenders();
/// assert_eq!(all[0], Contender::Ours(Method::DEFAULT));
/// assert!(all.contains(&Contender::Ours(Method::Sampled { step: 0.01 })));
/// assert_eq!(all.contains(&Contender::Parry), cfg!(feature = "parry-peer"));
/// ```
pub fn default_contenders() -> Vec<Contender> {
    let mut all = vec![
        Contender::Ours(Method::DEFAULT),
        Contender::Ours("adaptive-paper".parse().expect("a method")),
        Contender::Ours(Method::Advance),
    ];
    all.extend([1.0, 0.1, 0.01, 0.001].map(|step| Contender::Ours(Method::Sampled { step })));
    if cfg!(feature = "parry-peer") {
        all.push(Contender::Parry);
    }
    all
}

/// A verdict on one scene: the first contact time, if any, and the pair.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// First contact time and the two bodies.
    pub contact: Option<(f64, [String; 2])>,
}

/// One contender's totals over all scenes (the JSON's `methods[]`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodSummary {
    /// The contender's name, as `--methods` takes it.
    pub method: String,
    /// Median over scenes of the wall time of one whole-scene check, in microseconds.
    pub median_us: f64,
    /// Scenes where the reference finds a collision and this method none.
    pub missed: usize,
    /// Scenes where this method reports a contact where the reference proves none.
    pub invented: usize,
    /// Largest |t − t_ref| of the first contact over scenes where both find one; null when
    /// there is none.
    pub max_time_error: Option<f64>,
    /// Scenes this method could not check (parry refusing a shape or a query).
    pub unsupported: usize,
}

/// A scene where the parry peer and the reference disagree by more than the invented slack.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Disagreement {
    /// The scene's name.
    pub scene: String,
    /// Reference first contact time, if any.
    pub reference: Option<f64>,
    /// Parry's, if any.
    pub parry: Option<f64>,
    /// Why: which way they differ.
    pub what: String,
}

/// The whole comparison (the JSON of `workcell compare --json`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// Number of scenes.
    pub scenes: usize,
    /// Scenes in which the reference finds a collision.
    pub colliding: usize,
    /// One entry per contender, in the order given.
    pub methods: Vec<MethodSummary>,
    /// Scenes on which the parry peer and the reference disagree (empty without parry).
    pub disagreements: Vec<Disagreement>,
    /// Threads of the pool the checks ran on.
    pub threads: usize,
}

/// A scene to compare on, with its name for reports.
pub struct NamedScene {
    /// Usually the file's name.
    pub name: String,
    /// The scene.
    pub scene: Scene,
}

/// Refuses a contender that cannot check one of the scenes, as [`validate`] says (a
/// `sampled` step too fine for its horizon), naming the scene as the file.
///
/// ```
/// use workcell::compare::{validate_contenders, Contender, NamedScene};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let scenes = [NamedScene { name: "tunnelling.json".into(), scene }];
/// let fine: Contender = "sampled:1e-12".parse()?; // 10¹² looks over its 1 s horizon
/// let e = validate_contenders(&scenes, &[fine]).unwrap_err();
/// assert_eq!(e.file, std::path::Path::new("tunnelling.json"));
/// assert!(validate_contenders(&scenes, &["sampled:0.01".parse()?]).is_ok());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn validate_contenders(
    scenes: &[NamedScene],
    contenders: &[Contender],
) -> Result<(), InputError> {
    for named in scenes {
        for &c in contenders {
            if let Contender::Ours(method) = c {
                let opts = CheckOptions {
                    method,
                    ..CheckOptions::default()
                };
                validate(&named.scene, &opts)
                    .map_err(|e| e.in_file(std::path::Path::new(&named.name)))?;
            }
        }
    }
    Ok(())
}

/// Runs every contender on every scene; `progress` is told after each scene. A method that
/// cannot check a scene ([`validate`]: a `sampled` step too fine for its horizon) counts
/// that scene as unsupported, as parry does for shapes it refuses.
///
/// ```
/// use workcell::compare::{compare, NamedScene};
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/tunnelling.json");
/// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
/// let scenes = [NamedScene { name: "tunnelling.json".into(), scene }];
/// // The needle crosses the block between two samples: sampling once a second misses it.
/// let contenders = ["adaptive".parse()?, "sampled:1".parse()?];
/// let mut told = 0;
/// let result = compare(&scenes, &contenders, |_| told += 1);
/// assert_eq!((result.scenes, result.colliding, told), (1, 1, 1));
/// assert_eq!((result.methods[0].method.as_str(), result.methods[0].missed), ("adaptive", 0));
/// assert_eq!((result.methods[1].method.as_str(), result.methods[1].missed), ("sampled:1", 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn compare(
    scenes: &[NamedScene],
    contenders: &[Contender],
    mut progress: impl FnMut(usize),
) -> Comparison {
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); contenders.len()];
    let mut summaries: Vec<MethodSummary> = contenders
        .iter()
        .map(|c| MethodSummary {
            method: c.to_string(),
            median_us: f64::NAN,
            missed: 0,
            invented: 0,
            max_time_error: None,
            unsupported: 0,
        })
        .collect();
    let mut disagreements = Vec::new();
    let mut colliding = 0;
    for (k, named) in scenes.iter().enumerate() {
        let scene = &named.scene;
        let (h0, h1) = scene.horizon();
        let span = (h1 - h0).max(f64::MIN_POSITIVE);
        let reference = check(
            scene,
            &CheckOptions {
                time_tol: Some(REFERENCE_TIME_TOL * span),
                ..CheckOptions::default()
            },
        );
        colliding += usize::from(reference.collision);
        let slack = INVENTED_SLACK * span;
        for ((contender, summary), times) in contenders.iter().zip(&mut summaries).zip(&mut times) {
            let (verdict, seconds) = match timed(|| run(scene, *contender)) {
                (Some(v), s) => (v, s),
                (None, _) => {
                    summary.unsupported += 1;
                    continue;
                }
            };
            times.push(seconds * 1e6);
            let judged = judge(&reference, &verdict, slack);
            summary.missed += usize::from(judged.missed);
            summary.invented += usize::from(judged.invented);
            if let Some(e) = judged.time_error {
                summary.max_time_error = Some(summary.max_time_error.map_or(e, |m| m.max(e)));
            }
            if *contender == Contender::Parry {
                if let Some(what) = judged.disagreement(slack) {
                    disagreements.push(Disagreement {
                        scene: named.name.clone(),
                        reference: reference.first_contact.as_ref().map(|c| c.time),
                        parry: verdict.contact.as_ref().map(|c| c.0),
                        what,
                    });
                }
            }
        }
        progress(k + 1);
    }
    for (summary, times) in summaries.iter_mut().zip(&mut times) {
        summary.median_us = median(times);
    }
    Comparison {
        scenes: scenes.len(),
        colliding,
        methods: summaries,
        disagreements,
        threads: rayon::current_num_threads(),
    }
}

/// One check by `contender`; `None` when it cannot handle the scene.
fn run(scene: &Scene, contender: Contender) -> Option<Verdict> {
    match contender {
        Contender::Ours(method) => {
            let opts = CheckOptions {
                method,
                ..CheckOptions::default()
            };
            validate(scene, &opts).ok()?;
            let report = check(scene, &opts);
            Some(Verdict {
                contact: report.first_contact.map(|c| (c.time, c.bodies)),
            })
        }
        Contender::Parry => parry(scene),
    }
}

#[cfg(feature = "parry-peer")]
fn parry(scene: &Scene) -> Option<Verdict> {
    // The same candidate pairs as our checker: both get the broad phase.
    let pairs = crate::collision::candidate_pairs(scene, scene.delta);
    let report = crate::collision::check_with_parry(scene, &pairs, scene.delta);
    report.unsupported.is_empty().then_some(Verdict {
        contact: report.first_contact,
    })
}

#[cfg(not(feature = "parry-peer"))]
fn parry(_: &Scene) -> Option<Verdict> {
    unreachable!("`parry` is refused when parsing without the feature parry-peer")
}

/// The result of `f` and the mean wall time of one call in seconds, repeating `f` until
/// [`MIN_TIMED`] has passed.
fn timed<T>(mut f: impl FnMut() -> T) -> (T, f64) {
    let start = Instant::now();
    let first = f();
    let mut calls = 1u32;
    while start.elapsed() < MIN_TIMED {
        std::hint::black_box(f());
        calls += 1;
    }
    (first, start.elapsed().as_secs_f64() / f64::from(calls))
}

fn median(xs: &mut [f64]) -> f64 {
    if xs.is_empty() {
        return f64::NAN;
    }
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    }
}

/// A verdict against the reference on one scene.
#[derive(Debug, PartialEq)]
struct Judged {
    missed: bool,
    invented: bool,
    time_error: Option<f64>,
}

impl Judged {
    /// Why a peer's verdict disagrees with the reference, if it does beyond `slack`.
    fn disagreement(&self, slack: f64) -> Option<String> {
        if self.missed {
            Some("the reference finds a collision, parry none".into())
        } else if self.invented {
            Some("parry reports a contact where the reference proves the distance >= delta".into())
        } else {
            match self.time_error {
                Some(e) if e > slack => Some(format!("first contact times differ by {e:.3e}")),
                _ => None,
            }
        }
    }
}

fn judge(reference: &CheckReport, verdict: &Verdict, slack: f64) -> Judged {
    match (&reference.first_contact, &verdict.contact) {
        (None, None) => Judged {
            missed: false,
            invented: false,
            time_error: None,
        },
        (Some(_), None) => Judged {
            missed: true,
            invented: false,
            time_error: None,
        },
        (None, Some(_)) => Judged {
            missed: false,
            invented: true,
            time_error: None,
        },
        (Some(r), Some((t, _))) => Judged {
            missed: false,
            // Before the reference's certified prefix ends the distance is ≥ δ.
            invented: *t < reference.safe_until - slack,
            time_error: Some((t - r.time).abs()),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contenders_parse_and_print_alike() {
        for c in default_contenders() {
            assert_eq!(c.to_string().parse::<Contender>().unwrap(), c);
        }
        assert_eq!(
            "parry".parse::<Contender>().is_ok(),
            cfg!(feature = "parry-peer")
        );
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(median(&mut []).is_nan());
    }
}
