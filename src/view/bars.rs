//! A robot's lane of a chart: its activities as bars, each of a kind with its colour, from a
//! solve result's segments and changes or, for a scene's robot, from its samples alone.

use crate::wcp::legs_json::{LegJson, PieceJson};
use crate::wcp::remedy_json::ChangeJson;
use crate::wcp::report::{ResultJson, SegmentJson};
use serde::Serialize;

/// One activity of a robot.
#[derive(Clone, Debug, Serialize)]
pub struct Bar {
    /// `move`, `task`, `wait`, `pause`, `park`, `slow`, `detour`, `aside` or `still`.
    pub kind: &'static str,
    /// What it is in words, e.g. `task weld-3` or `move home -> weld-2`.
    pub label: String,
    /// The task's name for a task, else empty: what a bar shows when it fits.
    pub short: String,
    /// Start time.
    pub start: f64,
    /// End time.
    pub end: f64,
}

/// Every activity kind with its colour and its legend entry, in legend order.
pub const KINDS: [(&str, &str, &str); 9] = [
    ("move", "#90a4ae", "move"),
    ("task", "#1565c0", "task"),
    ("wait", "#ffb300", "wait at a node"),
    ("pause", "#ef6c00", "pause on a move"),
    ("slow", "#8e24aa", "slowed move"),
    ("detour", "#00897b", "detour"),
    ("aside", "#6d4c41", "move to step aside"),
    ("park", "#d81b60", "parked aside"),
    ("still", "#e0e0e0", "standing still"),
];

/// The colour of an activity kind.
pub fn kind_colour(kind: &str) -> &'static str {
    KINDS
        .iter()
        .find(|k| k.0 == kind)
        .map_or("#9e9e9e", |k| k.1)
}

/// A scene's robot has no activities, only samples: its spans of motion and of rest.
/// Each sample is `[t, state...]`: a pose, or an arm's joint angles.
pub(super) fn still_and_moving<S: AsRef<[f64]>>(samples: &[S]) -> Vec<Bar> {
    let mut bars: Vec<Bar> = Vec::new();
    for w in samples.windows(2) {
        let (a, b) = (w[0].as_ref(), w[1].as_ref());
        let kind = if a[1..] == b[1..] { "still" } else { "move" };
        match bars.last_mut() {
            Some(bar) if bar.kind == kind => bar.end = b[0],
            _ => bars.push(Bar {
                kind,
                label: if kind == "move" { "moving" } else { "still" }.to_owned(),
                short: String::new(),
                start: a[0],
                end: b[0],
            }),
        }
    }
    bars
}

/// What a move is: planned, or changed by a remedy. The rounds' changes say which remedy
/// touched it (solve); without them (evaluate) the changed leg's pieces tell.
fn move_kind(robot: &str, on: &str, legs: &[LegJson], changes: &[&ChangeJson]) -> &'static str {
    let Some(leg) = legs.iter().find(|l| l.robot == robot && l.on == on) else {
        return "move";
    };
    let touched = |kind: fn(&ChangeJson) -> Option<(&str, &str)>| {
        changes
            .iter()
            .filter_map(|c| kind(c))
            .any(|(r, o)| r == robot && o == on)
    };
    if touched(|c| match c {
        ChangeJson::Detour(d) => Some((&d.robot, &d.on)),
        _ => None,
    }) {
        return "detour";
    }
    let slowed = leg.pieces.iter().any(|p| match p {
        PieceJson::Go { go } => go.scale > 1.0,
        PieceJson::Hold { .. } => false,
    });
    if slowed {
        return "slow";
    }
    let holds: Vec<&str> = leg
        .pieces
        .iter()
        .filter_map(|p| match p {
            PieceJson::Hold { reason, .. } => Some(*reason),
            PieceJson::Go { .. } => None,
        })
        .collect();
    if holds.contains(&"park") {
        "aside"
    } else if holds.is_empty() {
        "detour"
    } else {
        "move"
    }
}

/// A segment of a solve result's schedule as a bar of robot `name`'s lane: what it does,
/// its tooltip, and the text it shows when wide enough (a task's name).
pub(super) fn bar_of(
    name: &str,
    s: &SegmentJson,
    result: &ResultJson,
    changes: &[&ChangeJson],
) -> Bar {
    let place = |n: &str| {
        if n == name {
            "home".to_owned()
        } else {
            n.to_owned()
        }
    };
    let on = match s.to {
        Some(to) if s.at == name && to == name => "excursion from home".to_owned(),
        Some(to) => format!("move {} -> {}", place(s.at), place(to)),
        None => String::new(),
    };
    let (kind, label, short) = match s.activity {
        "task" => ("task", format!("task {}", s.at), s.at.to_owned()),
        "wait" => ("wait", format!("wait at {}", place(s.at)), String::new()),
        "pause" => ("pause", format!("pause on {on}"), String::new()),
        "park" => ("park", format!("parked aside on {on}"), String::new()),
        _ => (
            move_kind(name, &on, &result.legs, changes),
            on,
            String::new(),
        ),
    };
    Bar {
        kind,
        label,
        short,
        start: s.start,
        end: s.end,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leg(pieces: Vec<PieceJson>) -> LegJson {
        LegJson {
            robot: "R1".to_owned(),
            leg: 1,
            on: "move a -> b".to_owned(),
            pieces,
        }
    }

    fn go(scale: f64) -> PieceJson {
        use crate::wcp::legs_json::GoJson;
        PieceJson::Go {
            go: GoJson {
                primitives: Vec::new(),
                joints: Vec::new(),
                scale,
            },
        }
    }

    fn hold(reason: &'static str) -> PieceJson {
        PieceJson::Hold { hold: 1.0, reason }
    }

    /// A changed move is told by its pieces, or by the round that changed it.
    #[test]
    fn moves_are_told_apart_by_their_remedy() {
        let kind = |pieces, changes: &[&ChangeJson]| {
            move_kind("R1", "move a -> b", &[leg(pieces)], changes)
        };
        assert_eq!(move_kind("R1", "move a -> b", &[], &[]), "move");
        assert_eq!(kind(vec![go(2.0)], &[]), "slow");
        assert_eq!(kind(vec![go(1.0), hold("park"), go(1.0)], &[]), "aside");
        assert_eq!(kind(vec![go(1.0), hold("pause"), go(1.0)], &[]), "move");
        assert_eq!(kind(vec![go(1.0)], &[]), "detour");
        let detour = ChangeJson::Detour(crate::wcp::remedy_json::DetourJson {
            robot: "R1".to_owned(),
            on: "move a -> b".to_owned(),
            around: "R2".to_owned(),
            path: Vec::new(),
        });
        assert_eq!(kind(vec![go(2.0)], &[&detour]), "detour");
        // Another robot's move is not this one.
        assert_eq!(
            move_kind("R2", "move a -> b", &[leg(vec![go(2.0)])], &[]),
            "move"
        );
    }
}
