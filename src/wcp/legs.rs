//! How a robot makes each move of its route, once the feedback loop has changed it.
//!
//! A route visits nodes (home, tasks, home); between two nodes the robot makes a *leg*. By
//! default a leg is the planned move between the two nodes, started as soon as the robot is
//! ready. The loop's remedies change legs, never the motion model: a leg may start after a
//! wait at its start node, and its motion may be replaced by a chain of pieces, each either
//! a certified motion (a detour, a way to a parking pose and back, the two halves of a move
//! cut where it pauses), possibly run slower, or a hold at the current pose. Every motion is
//! timed by the planner's model, so the speed, acceleration and turn-rate limits hold
//! whatever the remedies.

use crate::planning::PlannedMove;
use std::sync::Arc;

/// One leg of a robot's route: the move from one node to the next.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Leg {
    /// How long the robot waits at the start node before it leaves.
    pub wait: f64,
    /// The motion, when it is not the move planned between the two nodes; `None` is that
    /// move. The pieces start at the start node's pose and end at the end node's.
    pub pieces: Option<Arc<[Piece]>>,
}

impl Leg {
    /// The default leg: the planned move, at once.
    pub const DEFAULT: Leg = Leg {
        wait: 0.0,
        pieces: None,
    };

    /// True for the default leg.
    ///
    /// ```
    /// use workcell::wcp::legs::Leg;
    /// assert!(Leg::DEFAULT.is_default() && Leg::default().is_default());
    /// assert!(!Leg { wait: 0.5, ..Leg::DEFAULT }.is_default());
    /// ```
    pub fn is_default(&self) -> bool {
        self.wait == 0.0 && self.pieces.is_none()
    }
}

/// One piece of a changed leg.
#[derive(Clone, Debug, PartialEq)]
pub enum Piece {
    /// A motion certified clear of the fixtures, run `scale` (≥ 1) times slower than timed.
    Go {
        /// The motion, starting at rest where the robot is.
        motion: Arc<PlannedMove>,
        /// Time stretch: 1 as planned, 2 twice as slow.
        scale: f64,
    },
    /// Standing still where the robot is.
    Hold {
        /// How long.
        duration: f64,
        /// Why, for reports.
        reason: HoldReason,
    },
}

/// Why a robot holds still in the middle of a leg.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoldReason {
    /// Waiting at a point of its path for another robot to pass.
    Pause,
    /// Stepped aside to a parking pose, out of another robot's way.
    Park,
}

impl Piece {
    /// The duration of the piece.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::Pose;
    /// use workcell::planning::{plan_move, PlannerOptions, RobotLimits};
    /// use workcell::wcp::legs::{HoldReason, Piece};
    /// let limits = RobotLimits { max_speed: 1.0, max_accel: 2.0, max_turn_rate: 1.0 };
    /// let (a, b) = (Pose::new(0.0, 0.0, 0.0), Pose::new(4.0, 0.0, 0.0));
    /// let m = plan_move(&[ConvexPolygon::rectangle(1.0, 1.0)?], &limits, &[], 0.01, a, b, &PlannerOptions::default())?;
    /// let d = m.duration;
    /// assert_eq!(Piece::Go { motion: Arc::new(m), scale: 2.0 }.duration(), 2.0 * d);
    /// assert_eq!(Piece::Hold { duration: 1.5, reason: HoldReason::Pause }.duration(), 1.5);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn duration(&self) -> f64 {
        match self {
            Piece::Go { motion, scale } => motion.duration * scale,
            Piece::Hold { duration, .. } => *duration,
        }
    }
}

/// Every robot's legs, robot by robot; a robot's list may be shorter than its route (the
/// missing legs are default). A robot with no task may have one leg from home to home: an
/// excursion out of another robot's way.
pub type Legs = Vec<Arc<Vec<Leg>>>;

/// The leg `m` of robot `r` in `legs`, default if not listed.
///
/// ```
/// use workcell::wcp::legs::{default_legs, leg, with_leg, Leg};
/// let legs = with_leg(&default_legs(2), 0, 1, Leg { wait: 2.0, ..Leg::DEFAULT });
/// assert_eq!(leg(&legs, 0, 1).wait, 2.0);
/// assert_eq!(leg(&legs, 0, 7), &Leg::DEFAULT); // beyond the list: default
/// ```
pub fn leg(legs: &[Arc<Vec<Leg>>], r: usize, m: usize) -> &Leg {
    legs.get(r).and_then(|l| l.get(m)).unwrap_or(&Leg::DEFAULT)
}

/// Default legs for `robots` robots.
///
/// ```
/// use workcell::wcp::legs::default_legs;
/// let legs = default_legs(3);
/// assert_eq!(legs.len(), 3);
/// assert!(legs.iter().all(|l| l.is_empty())); // every leg the planned move, at once
/// ```
pub fn default_legs(robots: usize) -> Legs {
    // One shared empty list: a robot's list is replaced, never changed in place.
    let none = Arc::new(Vec::new());
    (0..robots).map(|_| none.clone()).collect()
}

/// `legs` with robot `r`'s leg `m` replaced.
///
/// ```
/// use workcell::wcp::legs::{default_legs, with_leg, Leg};
/// let none = default_legs(2);
/// let waits = with_leg(&none, 1, 2, Leg { wait: 1.0, ..Leg::DEFAULT });
/// assert_eq!(waits[1].len(), 3); // legs 0 and 1 default, leg 2 waits
/// assert!(none[1].is_empty()); // the original is unchanged
/// // Setting it back to default trims the list again.
/// assert_eq!(with_leg(&waits, 1, 2, Leg::DEFAULT), none);
/// ```
pub fn with_leg(legs: &Legs, r: usize, m: usize, new: Leg) -> Legs {
    let mut out = legs.clone();
    let mut list = (*out[r]).clone();
    if list.len() <= m {
        list.resize(m + 1, Leg::DEFAULT);
    }
    list[m] = new;
    while list.last().is_some_and(Leg::is_default) {
        list.pop();
    }
    out[r] = Arc::new(list);
    out
}
