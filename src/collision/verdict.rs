//! The outcome of a check in one value: free, a contact, or unresolved.
//!
//! [`CheckReport`] keeps every figure a check produces; [`CheckReport::verdict`] says what
//! they amount to, so that callers (the command line, the feedback loop, embedders) decide
//! on one enum instead of re-reading `first_contact`, `budget_exhausted` and `certified`.

use super::{BudgetExhausted, CheckReport, Contact};
use std::fmt;

/// What a check found. See [`CheckReport::verdict`].
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// No pair comes closer than δ over the whole horizon.
    Free {
        /// Whether that is proven ([`CheckReport::certified`]): false with a method that
        /// proves nothing, or when some interval only grazes δ or could not be resolved in
        /// f64 (see [`super::Stats`]).
        certified: bool,
    },
    /// Two bodies come closer than δ. The contact is always real: its distance is exact.
    Contact {
        /// The earliest contact: time, the pair (a robot first) and the distance.
        contact: Contact,
        /// Whether it is proven to be the first (to the time tolerance): everything before
        /// [`CheckReport::safe_until`] is certified free.
        certified: bool,
    },
    /// A pair spent its work budget ([`super::CheckOptions::max_work_per_pair`]) before a
    /// proof or a witness: free until `budget.time` (see [`CheckReport::safe_until`]),
    /// unknown after it.
    Unresolved {
        /// Where, and which pair.
        budget: BudgetExhausted,
    },
}

impl Verdict {
    /// True for [`Verdict::Free`] with a proof: the only verdict on which a schedule may be
    /// declared collision-free.
    ///
    /// ```
    /// use workcell::collision::Verdict;
    /// assert!(Verdict::Free { certified: true }.is_certified_free());
    /// assert!(!Verdict::Free { certified: false }.is_certified_free());
    /// ```
    pub fn is_certified_free(&self) -> bool {
        matches!(self, Verdict::Free { certified: true })
    }

    /// The first contact, for [`Verdict::Contact`].
    ///
    /// ```
    /// use workcell::collision::Verdict;
    /// assert!(Verdict::Free { certified: true }.contact().is_none());
    /// ```
    pub fn contact(&self) -> Option<&Contact> {
        match self {
            Verdict::Contact { contact, .. } => Some(contact),
            _ => None,
        }
    }
}

impl CheckReport {
    /// The report's outcome as one [`Verdict`]: a first contact if there is one, else an
    /// exhausted work budget, else free (certified or not).
    ///
    /// ```
    /// use workcell::collision::{check, Body, CheckOptions, Scene, Verdict};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::{Pose, Trajectory};
    ///
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// // A slides from x = 0 to x = 10 in one second, through B standing at x = 5.
    /// let path = Trajectory::from_poses([
    ///     (0.0, Pose::new(0.0, 0.0, 0.0)),
    ///     (1.0, Pose::new(10.0, 0.0, 0.0)),
    /// ])?;
    /// let mut scene = Scene::new(0.01)?;
    /// scene.add(Body::robot("A", square.clone(), path))?;
    /// let wall = ConvexPolygon::from_vertices(&[[4.5, -0.5], [5.5, -0.5], [5.5, 0.5], [4.5, 0.5]])?;
    /// scene.add(Body::obstacle("B", &wall))?;
    /// match check(&scene, &CheckOptions::default()).verdict() {
    ///     Verdict::Contact { contact, certified } => {
    ///         assert_eq!(contact.bodies, ["A".to_owned(), "B".to_owned()]);
    ///         assert!(contact.time < 0.5 && contact.distance < 0.01 && certified);
    ///     }
    ///     other => panic!("expected a contact, got {other}"),
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn verdict(&self) -> Verdict {
        match (&self.first_contact, &self.budget_exhausted) {
            (Some(c), _) => Verdict::Contact {
                contact: c.clone(),
                certified: self.certified,
            },
            (None, Some(b)) => Verdict::Unresolved { budget: b.clone() },
            (None, None) => Verdict::Free {
                certified: self.certified,
            },
        }
    }

    /// Up to when the check proved every pair δ apart: `safe_until` when the report is
    /// certified (no graze, which proves only δ·(1 − grazing_tol), nothing unresolved, no
    /// budget run out, a method that proves), else nothing. What [`super::check_known`] may
    /// be told of the same bodies, over the times they move alike.
    ///
    /// ```
    /// use workcell::collision::{check, Body, CheckOptions, Method, Scene};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::{Pose, Trajectory};
    /// // A square drives at 1 into one standing 6 ahead: they meet near t = 5.
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let drive = Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0)), (10.0, Pose::new(10.0, 0.0, 0.0))])?;
    /// let stand = Trajectory::from_poses([(0.0, Pose::new(6.0, 0.0, 0.0)), (10.0, Pose::new(6.0, 0.0, 0.0))])?;
    /// let scene = Scene::with_bodies(0.1, [Body::robot("A", square.clone(), drive), Body::robot("B", square, stand)])?;
    /// let proved = check(&scene, &CheckOptions::default());
    /// assert_eq!(proved.proven_until(), Some(proved.safe_until));
    /// assert!(proved.safe_until > 4.8 && proved.safe_until < 5.0);
    /// // Samples prove nothing.
    /// let sampled = CheckOptions { method: Method::Sampled { step: 0.01 }, ..CheckOptions::default() };
    /// assert_eq!(check(&scene, &sampled).proven_until(), None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn proven_until(&self) -> Option<f64> {
        self.certified.then_some(self.safe_until)
    }
}

/// One line: `free (certified)`, `contact between A and B at t = 0.45 (distance 0)`, or
/// `unresolved: A and B spent their work budget at t = 2`.
impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let proof = |certified: bool| {
            if certified {
                "certified"
            } else {
                "not certified"
            }
        };
        match self {
            Verdict::Free { certified } => write!(f, "free ({})", proof(*certified)),
            Verdict::Contact { contact, certified } => write!(
                f,
                "contact between {} and {} at t = {} (distance {:e}; {})",
                contact.bodies[0],
                contact.bodies[1],
                contact.time,
                contact.distance,
                proof(*certified)
            ),
            Verdict::Unresolved { budget } => write!(
                f,
                "unresolved: {} and {} spent their work budget ({} evaluations) at t = {}",
                budget.bodies[0], budget.bodies[1], budget.work, budget.time
            ),
        }
    }
}
