//! The ways of searching one merged interval for a contact, behind one interface.

use super::eta::Eta;
use super::span::{PairSettings, Probe, Span, Stop};
use super::stats::Stats;
use super::{adaptive, advance, sampled};
use crate::motion::BoundKind;
use std::fmt;
use std::str::FromStr;

/// How the checker searches each merged interval of each pair. All methods share the merged
/// grid, η and its narrow phase, and the result type; they differ in where they look.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Table 1 of Feyeux & Landry: certify an interval by the Schwarzer-Saha-Latombe
    /// condition with the given λ, or bisect it. With [`BoundKind::Rigorous`] it adds the
    /// convexity certificate and misses nothing; with [`BoundKind::Paper`] (eq. 12) it is the
    /// paper's method, which trusts the given velocities.
    Adaptive(BoundKind),
    /// The static approach of many motion-planning stacks: the distance at the samples and
    /// every `step` time units from the start of the horizon, nothing in between. Proves
    /// nothing; misses whatever happens between two looks.
    Sampled {
        /// Time between two extra looks, in the scene's time unit.
        step: f64,
    },
    /// Conservative advancement, as in Box2D's and FCL's time of impact: from a free time,
    /// step forward by (η − δ) / λ', where λ' bounds how fast the pair can close in (the
    /// rigorous λ per unit of the interval). Never steps over a contact, but needs ever more
    /// steps while a pair glides near δ; a step is never shorter than the time tolerance,
    /// and such a step counts as a graze.
    Advance,
}

impl Method {
    /// The default: adaptive with the rigorous bound.
    pub const DEFAULT: Method = Method::Adaptive(BoundKind::Rigorous);

    /// Whether a collision-free verdict of this method is a proof (up to grazes).
    ///
    /// ```
    /// use workcell::collision::Method;
    /// assert!(Method::DEFAULT.proves_free());
    /// // Sampling and the paper's velocity-based bound can miss a collision between samples.
    /// assert!(!"sampled:0.01".parse::<Method>()?.proves_free());
    /// assert!(!"adaptive-paper".parse::<Method>()?.proves_free());
    /// # Ok::<(), String>(())
    /// ```
    pub fn proves_free(self) -> bool {
        !matches!(
            self,
            Method::Sampled { .. } | Method::Adaptive(BoundKind::Paper)
        )
    }
}

impl Default for Method {
    fn default() -> Self {
        Method::DEFAULT
    }
}

/// The name on the command line: `adaptive`, `adaptive-paper`, `sampled:STEP`, `advance`.
impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Method::Adaptive(BoundKind::Rigorous) => f.write_str("adaptive"),
            Method::Adaptive(BoundKind::Paper) => f.write_str("adaptive-paper"),
            Method::Sampled { step } => write!(f, "sampled:{step}"),
            Method::Advance => f.write_str("advance"),
        }
    }
}

impl FromStr for Method {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "adaptive" => Ok(Method::Adaptive(BoundKind::Rigorous)),
            "adaptive-paper" => Ok(Method::Adaptive(BoundKind::Paper)),
            "advance" => Ok(Method::Advance),
            _ => match s.strip_prefix("sampled:").map(str::parse::<f64>) {
                Some(Ok(step)) if step.is_finite() && step > 0.0 => Ok(Method::Sampled { step }),
                Some(_) => Err(format!(
                    "`{s}`: the step of `sampled:STEP` must be a positive number of time units"
                )),
                None => Err(format!(
                    "unknown method `{s}`: expected adaptive, adaptive-paper, sampled:STEP or advance"
                )),
            },
        }
    }
}

/// What one thread reuses from pair to pair.
#[derive(Default)]
pub struct Scratch {
    /// The bisection stack of the adaptive method.
    stack: Vec<(Probe, Probe)>,
}

impl Method {
    /// Searches one merged interval, both ends evaluated and the left one free: `Ok` when
    /// the method finds no contact in it, else why it stopped.
    pub(super) fn search(
        self,
        eta: &mut Eta,
        span: &Span,
        ends: (Probe, Probe),
        s: &PairSettings,
        scratch: &mut Scratch,
        stats: &mut Stats,
    ) -> Result<(), Stop> {
        match self {
            Method::Adaptive(bound) => {
                adaptive::search(eta, span, ends, bound, s, &mut scratch.stack, stats)
            }
            Method::Sampled { step } => sampled::search(eta, span, ends, step, s, stats),
            Method::Advance => advance::search(eta, span, ends, s, stats),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for name in ["adaptive", "adaptive-paper", "advance", "sampled:0.25"] {
            assert_eq!(name.parse::<Method>().unwrap().to_string(), name);
        }
        for bad in [
            "sampled:0",
            "sampled:-1",
            "sampled:x",
            "sampled:inf",
            "bisect",
        ] {
            assert!(bad.parse::<Method>().is_err(), "{bad}");
        }
    }
}
