//! The checker's input: bodies with their shapes and motions.

use crate::error::InputError;
use crate::geometry::{ConvexPolygon, Parts};
use crate::motion::{ArmMotion, LinkMotion, Motion, Pose, Trajectory};
use std::collections::HashSet;
use std::path::Path;
use std::sync::Arc;

/// A robot or an obstacle.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Name, unique in the scene.
    pub name: String,
    /// Shape in the body frame, whose origin is the rotation centre G: the body itself, or
    /// the convex hull of its `parts`.
    pub shape: ConvexPolygon,
    /// For a body that is not convex, the convex parts whose union it is (contract section
    /// 5), in the same frame; `None` for a convex body.
    pub parts: Option<Parts>,
    /// How the body moves.
    pub motion: Motion,
}

impl Body {
    /// A robot: `shape` in its own frame (whose origin G follows the trajectory and is the
    /// centre of rotation), moving along `trajectory`.
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::{Pose, Trajectory};
    /// let path = Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0)), (2.0, Pose::new(4.0, 0.0, 1.0))])?;
    /// let r = Body::robot("R1", ConvexPolygon::rectangle(1.0, 0.5)?, path);
    /// assert!(r.is_robot());
    /// assert_eq!(r.motion.pose_at(1.0).pos.x, 2.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn robot(name: impl Into<String>, shape: ConvexPolygon, trajectory: Trajectory) -> Self {
        Body {
            name: name.into(),
            shape,
            parts: None,
            motion: Motion::Sampled(trajectory),
        }
    }

    /// A robot made of convex parts (their union), given in its own frame, moving along
    /// `trajectory`; its `shape` is their hull.
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{Pose, Trajectory};
    /// let finger = ConvexPolygon::from_vertices(&[[0.5, -0.1], [1.2, -0.1], [1.2, 0.1], [0.5, 0.1]])?;
    /// let gripper = Parts::new(vec![ConvexPolygon::rectangle(1.0, 0.6)?, finger])?;
    /// let still = Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0))])?;
    /// let r = Body::robot_of_parts("R1", gripper, still);
    /// assert_eq!((r.shape.len(), r.parts.map(|p| p.len())), (6, Some(2)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn robot_of_parts(name: impl Into<String>, parts: Parts, trajectory: Trajectory) -> Self {
        Body {
            name: name.into(),
            shape: parts.hull().clone(),
            parts: (!parts.is_convex()).then_some(parts),
            motion: Motion::Sampled(trajectory),
        }
    }

    /// A fixed obstacle given in world coordinates. Its frame is moved to its centroid so
    /// that its bounding disc (eq. 13) is tight.
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::ConvexPolygon;
    /// let wall = ConvexPolygon::from_vertices(&[[4.0, -1.0], [6.0, -1.0], [6.0, 1.0], [4.0, 1.0]])?;
    /// let o = Body::obstacle("wall", &wall);
    /// assert!(!o.is_robot());
    /// assert_eq!(o.motion.pose_at(0.0).pos.x, 5.0);
    /// # Ok::<(), workcell::geometry::PolygonError>(())
    /// ```
    pub fn obstacle(name: impl Into<String>, world_shape: &ConvexPolygon) -> Self {
        let c = world_shape.centroid();
        Body {
            name: name.into(),
            shape: world_shape.translated(&c),
            parts: None,
            motion: Motion::Fixed(Pose { pos: c, theta: 0.0 }),
        }
    }

    /// A fixed obstacle made of convex parts given in world coordinates; its frame is moved
    /// to the centroid of their hull, as [`Body::obstacle`] does.
    ///
    /// ```
    /// use workcell::collision::Body;
    /// use workcell::geometry::{Outline, Parts};
    /// let l = Outline::new(&[[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]])?;
    /// let o = Body::obstacle_of_parts("L-fixture", &Parts::from_outline(&l)?);
    /// assert_eq!(o.parts.as_ref().map(|p| p.len()), Some(2));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn obstacle_of_parts(name: impl Into<String>, world_parts: &Parts) -> Self {
        let body = Body::obstacle(name, world_parts.hull());
        let c = body.motion.pose_at(0.0).pos;
        Body {
            parts: (!world_parts.is_convex()).then(|| world_parts.translated(&c)),
            ..body
        }
    }

    /// The links of an arm named `name` (contract section 6): one body per link, each given
    /// in its link's frame (origin at its joint, x along the link) as a convex shape or
    /// parts, all moved by `arm`. The links share the arm's name; [`Body::link`] tells them
    /// apart, and links of one arm are never checked against each other. Each link's radius
    /// about its joint is raised to its body's, so that the motion bound covers the body.
    /// [`super::Arm`] builds the same bodies, checking the counts.
    ///
    /// # Panics
    ///
    /// When `links` does not hold one body per link of `arm`.
    ///
    /// ```
    /// use workcell::collision::{Body, Scene};
    /// use workcell::geometry::{ConvexPolygon, Parts};
    /// use workcell::motion::{ArmMotion, JointSample, Pose};
    /// let bar = |l: f64| Parts::new(vec![ConvexPolygon::from_vertices(&[[-0.1, -0.1], [l + 0.1, -0.1], [l + 0.1, 0.1], [-0.1, 0.1]])?]);
    /// let links = vec![bar(1.0)?, bar(0.6)?];
    /// let s = |t: f64, q: [f64; 2]| JointSample { t, q: q.to_vec(), qd: Vec::new() };
    /// let reach = links.iter().map(|p| p.hull().radius()).collect();
    /// let arm = ArmMotion::new(Pose::new(0.0, 0.0, 0.0), vec![1.0, 0.6], reach, vec![s(0.0, [0.0, 0.0]), s(1.0, [1.0, -1.0])])?;
    /// let bodies = Body::arm("A1", arm, links);
    /// assert_eq!((bodies.len(), bodies[1].link()), (2, Some(1)));
    /// assert!(bodies[0].same_arm(&bodies[1]));
    /// let scene = Scene::with_bodies(0.01, bodies)?;
    /// assert_eq!(scene.pair_count(), 0); // links of one arm are not checked against each other
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn arm(name: impl Into<String>, arm: ArmMotion, links: Vec<Parts>) -> Vec<Body> {
        assert_eq!(links.len(), arm.links(), "one body per link of the arm");
        let name = name.into();
        // λ must bound the bodies' own points, whatever radii the arm was given.
        let radii: Vec<f64> = links.iter().map(|p| p.hull().radius()).collect();
        let arm = Arc::new(arm.covering(&radii));
        links
            .into_iter()
            .enumerate()
            .map(|(link, parts)| Body {
                name: name.clone(),
                shape: parts.hull().clone(),
                parts: (!parts.is_convex()).then_some(parts),
                motion: Motion::Link(LinkMotion::new(arm.clone(), link)),
            })
            .collect()
    }

    /// True for a body that moves: along a trajectory, or as a link of an arm.
    pub fn is_robot(&self) -> bool {
        matches!(self.motion, Motion::Sampled(_) | Motion::Link(_))
    }

    /// For a link of an arm, its index (0 at the base).
    pub fn link(&self) -> Option<usize> {
        match &self.motion {
            Motion::Link(l) => Some(l.link),
            _ => None,
        }
    }

    /// Whether both bodies are links of one arm (never checked against each other).
    pub fn same_arm(&self, other: &Body) -> bool {
        match (&self.motion, &other.motion) {
            (Motion::Link(a), Motion::Link(b)) => a.same_arm(b),
            _ => false,
        }
    }
}

/// Robots with trajectories and fixed obstacles, and the safety margin.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// δ: bodies closer than this collide. Length units of the scene.
    pub delta: f64,
    /// Robots first, then obstacles.
    pub bodies: Vec<Body>,
}

impl Scene {
    /// An empty scene of safety margin `delta` (length units of the scene); refuses a δ that
    /// is not a positive finite number. Add bodies with [`Scene::add`].
    ///
    /// ```
    /// use workcell::collision::Scene;
    /// let scene = Scene::new(0.01)?;
    /// assert!(scene.bodies.is_empty());
    /// for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
    ///     let e = Scene::new(bad).unwrap_err();
    ///     assert_eq!(e.field, "delta");
    /// }
    /// assert_eq!(
    ///     Scene::new(-1.0).unwrap_err().to_string(),
    ///     "field `delta`: must be a positive number, got -1"
    /// );
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn new(delta: f64) -> Result<Self, InputError> {
        check_delta(delta)?;
        Ok(Scene {
            delta,
            bodies: Vec::new(),
        })
    }

    /// A scene of `delta` with these bodies: [`Scene::new`] then [`Scene::add`] for each,
    /// with the names compared in one pass (for scenes of many bodies).
    ///
    /// ```
    /// use workcell::collision::{Body, Scene};
    /// use workcell::geometry::ConvexPolygon;
    /// let post = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let e = Scene::with_bodies(0.01, [Body::obstacle("post", &post), Body::obstacle("post", &post)])
    ///     .unwrap_err();
    /// assert_eq!(e.to_string(), "body \"post\", field `bodies[1].name`: another body has the same name");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_bodies(
        delta: f64,
        bodies: impl IntoIterator<Item = Body>,
    ) -> Result<Self, InputError> {
        let mut scene = Scene::new(delta)?;
        let mut names = HashSet::new();
        let mut obstacles: Vec<Body> = Vec::new();
        for (k, body) in bodies.into_iter().enumerate() {
            // A later link of the arm just added shares its name.
            let sibling = scene.bodies.last().is_some_and(|b| b.same_arm(&body));
            check_name(&body.name, k, |name| {
                !sibling && !names.insert(name.to_owned())
            })?;
            if body.is_robot() {
                scene.bodies.push(body);
            } else {
                obstacles.push(body);
            }
        }
        scene.bodies.append(&mut obstacles);
        Ok(scene)
    }

    /// Adds a robot or an obstacle. Its name must be non-empty and unique in the scene
    /// (compared with every body's: O(bodies)); robots are kept before obstacles, in the order
    /// added. Errors name the body and its field `bodies[k].name`, `k` its index once added.
    ///
    /// ```
    /// use workcell::collision::{Body, Scene};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::{Pose, Trajectory};
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let at_rest = Trajectory::from_poses([(0.0, Pose::new(0.0, 0.0, 0.0))])?;
    /// let mut scene = Scene::new(0.01)?;
    /// scene
    ///     .add(Body::obstacle("post", &square.translated(&[-3.0, 0.0].into())))?
    ///     .add(Body::robot("R1", square.clone(), at_rest))?;
    /// assert_eq!(scene.bodies[0].name, "R1"); // robots first
    /// assert_eq!(scene.pair_count(), 1);
    /// let e = scene.add(Body::obstacle("", &square)).unwrap_err();
    /// assert_eq!(e.reason, "a body needs a non-empty name");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add(&mut self, body: Body) -> Result<&mut Self, InputError> {
        let k = self.bodies.len();
        check_name(&body.name, k, |name| {
            self.bodies
                .iter()
                .any(|b| b.name == name && !b.same_arm(&body))
        })?;
        let at = if body.is_robot() {
            self.robot_count()
        } else {
            k
        };
        self.bodies.insert(at, body);
        Ok(self)
    }

    /// Earliest and latest sample time of any robot; `(0, 0)` without robots.
    ///
    /// ```
    /// use workcell::collision::{Body, Scene};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::{Pose, Trajectory};
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let path = |t0: f64, t1: f64| Trajectory::from_poses([(t0, Pose::new(0.0, 0.0, 0.0)), (t1, Pose::new(1.0, 0.0, 0.0))]);
    /// let mut scene = Scene::new(0.01)?;
    /// assert_eq!(scene.horizon(), (0.0, 0.0));
    /// scene.add(Body::robot("A", square.clone(), path(2.0, 5.0)?))?.add(Body::robot("B", square, path(1.0, 3.0)?))?;
    /// assert_eq!(scene.horizon(), (1.0, 5.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn horizon(&self) -> (f64, f64) {
        // A trajectory's times strictly increase: its first and last samples are its ends.
        let mut ends = self.bodies.iter().filter_map(|b| b.motion.span());
        match ends.next() {
            None => (0.0, 0.0),
            Some(first) => ends.fold(first, |(lo, hi), (t0, t1)| (lo.min(t0), hi.max(t1))),
        }
    }

    /// The pairs to check, in report order: robot-robot pairs, then robot-obstacle pairs.
    /// Obstacle pairs never change and are not checked.
    ///
    /// ```
    /// use workcell::collision::{Body, Scene};
    /// use workcell::geometry::ConvexPolygon;
    /// use workcell::motion::{Pose, Trajectory};
    /// let square = ConvexPolygon::rectangle(1.0, 1.0)?;
    /// let still = |x: f64| Trajectory::from_poses([(0.0, Pose::new(x, 0.0, 0.0))]);
    /// let mut scene = Scene::new(0.01)?;
    /// let wall = ConvexPolygon::from_vertices(&[[8.0, 8.0], [9.0, 8.0], [9.0, 9.0], [8.0, 9.0]])?;
    /// scene.add(Body::obstacle("wall", &wall))?;
    /// scene.add(Body::robot("A", square.clone(), still(0.0)?))?.add(Body::robot("B", square, still(3.0)?))?;
    /// // Bodies: A, B, wall (robots first). A-B, then each robot with the wall.
    /// assert_eq!(scene.pairs(), [(0, 1), (0, 2), (1, 2)]);
    /// assert_eq!(scene.pair_count(), 3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        let n = self.bodies.len();
        let robot = |i: &usize| self.bodies[*i].is_robot();
        let mut pairs = Vec::with_capacity(self.pair_count());
        let bodies = &self.bodies;
        for i in (0..n).filter(robot) {
            let apart = |j: &usize| robot(j) && !bodies[i].same_arm(&bodies[*j]);
            pairs.extend((i + 1..n).filter(apart).map(|j| (i, j)));
        }
        for i in (0..n).filter(robot) {
            pairs.extend((0..n).filter(|j| !robot(j)).map(|j| (i, j)));
        }
        pairs
    }

    /// The number of robots (bodies that move).
    pub fn robot_count(&self) -> usize {
        self.bodies.iter().filter(|b| b.is_robot()).count()
    }

    /// The number of pairs [`Scene::pairs`] gives, without listing them.
    pub fn pair_count(&self) -> usize {
        let robots = self.robot_count();
        let obstacles = self.bodies.len() - robots;
        // Links of one arm are consecutive: an arm of k links leaves out k(k − 1)/2 pairs.
        let mut siblings = 0;
        let mut run = 0;
        for (k, b) in self.bodies.iter().enumerate() {
            run = match k.checked_sub(1) {
                Some(p) if self.bodies[p].same_arm(b) => run + 1,
                _ => 0,
            };
            siblings += run;
        }
        robots * robots.saturating_sub(1) / 2 + robots * obstacles - siblings
    }

    /// The field of body `k` in its file: `robots[r]` (with `.links[l]` for a link of an
    /// arm, `r` counting an arm once) or `obstacles[o]`.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cells/paper-fig12a.json");
    /// let scene = workcell::cell::load_scene(path.as_ref())?.scene;
    /// assert_eq!(scene.field_of(1), "robots[1]");
    /// # Ok::<(), workcell::cell::InputError>(())
    /// ```
    pub fn field_of(&self, k: usize) -> String {
        let bodies = &self.bodies;
        let first_of_robot = |i: usize| i == 0 || !bodies[i - 1].same_arm(&bodies[i]);
        if bodies[k].is_robot() {
            let started = (0..k).filter(|&i| first_of_robot(i)).count();
            let r = started - usize::from(!first_of_robot(k));
            match bodies[k].link() {
                Some(l) => format!("robots[{r}].links[{l}]"),
                None => format!("robots[{r}]"),
            }
        } else {
            format!("obstacles[{}]", k - self.robot_count())
        }
    }
}

/// Refuses a δ that is not a positive finite number: the one rule for δ, whether given in
/// code, a file or an option. The error names field `delta` and no file.
pub(crate) fn check_delta(delta: f64) -> Result<(), InputError> {
    if delta.is_finite() && delta > 0.0 {
        return Ok(());
    }
    let reason = format!("must be a positive number, got {delta}");
    Err(InputError::new(Path::new(""), None, "delta", reason))
}

/// Refuses an empty name, or one that `taken` says another body has; `k` is the body's index.
fn check_name(name: &str, k: usize, taken: impl FnOnce(&str) -> bool) -> Result<(), InputError> {
    let field = format!("bodies[{k}].name");
    if name.is_empty() {
        let reason = "a body needs a non-empty name";
        return Err(InputError::new(Path::new(""), None, field, reason));
    }
    if let Some(reason) = name_fault(name) {
        return Err(InputError::new(Path::new(""), None, field, reason));
    }
    if taken(name) {
        let reason = "another body has the same name";
        return Err(InputError::new(Path::new(""), Some(name), field, reason));
    }
    Ok(())
}

/// The longest name, in characters: a name is copied into every report, round and
/// picture, and a search holds thousands of them (a 1 MB name made a conflict cell's search
/// take 4.8 GB).
pub const MAX_NAME_CHARS: usize = 256;

/// Why a name cannot be written into every output (a terminal, JSON, an SVG, a page): a
/// control character, a noncharacter that XML refuses, or more than [`MAX_NAME_CHARS`]
/// characters. `None` for a usable name. The message does not repeat the name, which may
/// hold an escape sequence.
///
/// ```
/// use workcell::collision::{name_fault, MAX_NAME_CHARS};
/// assert_eq!(name_fault("R1 ⟂ weld"), None);
/// assert_eq!(name_fault("R\u{1b}[2J").as_deref(), Some("a name may not hold control characters: U+001B at character 2"));
/// assert!(name_fault(&"R".repeat(MAX_NAME_CHARS)).is_none());
/// assert!(name_fault(&"R".repeat(MAX_NAME_CHARS + 1)).unwrap().contains("at most 256"));
/// ```
pub fn name_fault(name: &str) -> Option<String> {
    let chars = name.chars().take(MAX_NAME_CHARS + 1).count();
    if chars > MAX_NAME_CHARS {
        return Some(format!(
            "a name may hold at most {MAX_NAME_CHARS} characters (this one has {})",
            name.chars().count()
        ));
    }
    let (k, c) = name
        .chars()
        .enumerate()
        .find(|&(_, c)| c.is_control() || matches!(c, '\u{FFFE}' | '\u{FFFF}'))?;
    Some(format!(
        "a name may not hold control characters: U+{:04X} at character {}",
        c as u32,
        k + 1
    ))
}
