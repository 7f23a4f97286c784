//! The search's memory of schedules seen: a digest of routes, arm configurations and legs.

use crate::wcp::configurations::Assignment;
use crate::wcp::legs::{HoldReason, Leg, Legs, Piece};
use std::hash::{Hash, Hasher};

/// A 128-bit digest of routes, arm configurations and legs: two schedules with the same digest are the same
/// schedule (up to a collision of the hash, at odds of 2⁻¹²⁸ per pair).
pub(super) fn fingerprint(routes: &[Vec<usize>], legs: &Legs, assignment: &Assignment) -> u128 {
    digest(routes, assignment, |h| {
        for list in legs {
            hash_legs(list, h);
        }
    })
}

/// A 128-bit digest of every route and arm configuration and of robots `pair`'s legs: what
/// the remedies read of a schedule when they answer a collision of that pair.
pub(super) fn pair_fingerprint(
    routes: &[Vec<usize>],
    legs: &Legs,
    assignment: &Assignment,
    pair: (usize, usize),
) -> u128 {
    digest(routes, assignment, |h| {
        for r in [pair.0, pair.1] {
            r.hash(h);
            hash_legs(&legs[r], h);
        }
    })
}

#[allow(deprecated)]
type Sip = std::hash::SipHasher;

/// Routes and configurations, then what `more` adds, digested twice with different keys.
fn digest(routes: &[Vec<usize>], assignment: &Assignment, more: impl Fn(&mut Sip)) -> u128 {
    let half = |salt: u64| {
        // SipHash with fixed keys: the same on every run.
        #[allow(deprecated)]
        let mut h = Sip::new_with_keys(salt, !salt);
        routes.hash(&mut h);
        assignment.chosen().hash(&mut h);
        more(&mut h);
        h.finish()
    };
    (half(0x5eed) as u128) << 64 | half(0xfeed) as u128
}

/// One robot's legs: waits, and the pieces each leg is made of.
fn hash_legs(list: &[Leg], h: &mut Sip) {
    list.len().hash(h);
    for leg in list.iter() {
        leg.wait.to_bits().hash(h);
        let Some(pieces) = &leg.pieces else {
            0u8.hash(h);
            continue;
        };
        for piece in pieces.iter() {
            match piece {
                Piece::Go { motion, scale } => {
                    1u8.hash(h);
                    scale.to_bits().hash(h);
                    // An arm's motion is its joints.
                    for s in &motion.joints {
                        s.t.to_bits().hash(h);
                        s.q.iter().for_each(|a| a.to_bits().hash(h));
                    }
                    for p in &motion.primitives {
                        p.theta.to_bits().hash(h);
                        p.turn.to_bits().hash(h);
                        for v in &p.path {
                            (v.x.to_bits(), v.y.to_bits()).hash(h);
                        }
                    }
                }
                Piece::Hold { duration, reason } => {
                    2u8.hash(h);
                    duration.to_bits().hash(h);
                    (*reason == HoldReason::Park).hash(h);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::JointSample;
    use crate::planning::PlannedMove;
    use crate::wcp::legs::Leg;
    use std::sync::Arc;

    /// Two arm motions differ only in their joints (an arm's go piece has no primitives):
    /// different schedules, different digests.
    #[test]
    fn an_arms_joints_count() {
        let cell = crate::cell::load_cell(
            concat!(env!("CARGO_MANIFEST_DIR"), "/cells/scara-cell.json").as_ref(),
        )
        .unwrap()
        .cell;
        let store = crate::wcp::MoveStore::new(&cell, &crate::planning::PlannerOptions::default());
        let legs_with = |q: f64| -> Legs {
            let joints = vec![JointSample {
                t: 0.0,
                q: vec![q, 0.0],
                qd: vec![0.0; 2],
            }];
            let motion = Arc::new(PlannedMove {
                duration: 0.0,
                path: Vec::new(),
                samples: Vec::new(),
                primitives: Vec::new(),
                joints,
            });
            let leg = Leg {
                wait: 0.0,
                pieces: Some(vec![Piece::Go { motion, scale: 1.0 }].into()),
            };
            vec![Arc::new(vec![leg]), Arc::new(Vec::new())]
        };
        let routes = vec![vec![1], vec![]];
        let a = store.assignment();
        assert_eq!(
            fingerprint(&routes, &legs_with(0.5), a),
            fingerprint(&routes, &legs_with(0.5), a)
        );
        assert_ne!(
            fingerprint(&routes, &legs_with(0.5), a),
            fingerprint(&routes, &legs_with(0.6), a)
        );
    }
}
