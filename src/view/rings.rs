//! Collision rings: the rounds that collided at one place share one ring, numbered with
//! each of them, placed clear of the labels and led back to the contact point when moved.

use super::canvas::{circle, line, text, Frame, RING};
use super::labels::{text_width, Placer, Rect};
use super::model::Mark;
use svg::node::element::{Group, Rectangle};
use svg::Document;

/// Collisions this close on the picture (pixels) are one place: one ring for them all.
const SAME_PLACE: f64 = 2.0;

/// One ring: the collisions of one place, with their rounds' numbers ("!" for a check's
/// contact) in round order, and its half width (a ring widens into a pill for a list).
pub(super) struct Ring<'m> {
    at: &'m Mark,
    numbers: String,
    font: f64,
    half_width: f64,
}

/// The rings of `marks`: marks at one place (within [`SAME_PLACE`]) share one, numbered
/// with every round that collided there (a search that met the same collision again).
pub(super) fn rings_of<'m>(marks: &[&'m Mark], frame: &Frame) -> Vec<Ring<'m>> {
    let mut groups: Vec<(&Mark, Vec<String>)> = Vec::new();
    for mark in marks {
        let number = mark.round.map_or("!".to_owned(), |r| r.to_string());
        let (x, y) = frame.xy(mark.point[0], mark.point[1]);
        let same = groups.iter_mut().find(|(first, _)| {
            let (fx, fy) = frame.xy(first.point[0], first.point[1]);
            (fx - x).hypot(fy - y) <= SAME_PLACE
        });
        match same {
            Some((_, numbers)) => numbers.push(number),
            None => groups.push((mark, vec![number])),
        }
    }
    groups
        .into_iter()
        .map(|(at, numbers)| {
            let numbers = numbers.join(", ");
            let font = if numbers.len() > 2 { 8.0 } else { 11.0 };
            let half_width = RING.max(0.5 * text_width(&numbers, font) + 5.0);
            Ring {
                at,
                numbers,
                font,
                half_width,
            }
        })
        .collect()
}

/// Each ring with its numbers at the place [`ring_places`] chose, led back to the contact
/// point when moved. Leaders go under every ring, so that no leader crosses another
/// round's number.
pub(super) fn numbered_rings(
    mut doc: Document,
    rings: &[Ring],
    places: &[(f64, f64)],
    frame: &Frame,
) -> Document {
    for (ring, &(cx, cy)) in rings.iter().zip(places) {
        let (x, y) = frame.xy(ring.at.point[0], ring.at.point[1]);
        if (cx - x).hypot(cy - y) > 0.5 {
            doc = doc
                .add(
                    line(x, y, cx, cy)
                        .set("stroke", "#d50000")
                        .set("stroke-width", 0.8),
                )
                .add(circle(x, y, 2.0).set("fill", "#d50000"));
        }
    }
    for (ring, &(cx, cy)) in rings.iter().zip(places) {
        let hw = ring.half_width;
        let outline = Group::new()
            .set("fill", "white")
            .set("fill-opacity", 0.85)
            .set("stroke", "#d50000")
            .set("stroke-width", 2.5);
        let outline = match hw > RING {
            false => outline.add(circle(cx, cy, RING)),
            true => outline.add(
                Rectangle::new()
                    .set("x", cx - hw)
                    .set("y", cy - RING)
                    .set("width", 2.0 * hw)
                    .set("height", 2.0 * RING)
                    .set("rx", RING),
            ),
        };
        doc = doc.add(outline).add(
            text(
                cx,
                cy + ring.font * 0.36,
                &ring.numbers,
                ring.font,
                "#d50000",
            )
            .set("text-anchor", "middle")
            .set("font-weight", "bold"),
        );
    }
    doc
}

/// Where each ring goes: on its point when free, else on rings round it, away from the
/// rings already placed (rounds often collide at nearly one place).
pub(super) fn ring_places(rings: &[Ring], frame: &Frame, placer: &mut Placer) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for ring in rings {
        let (x, y) = frame.xy(ring.at.point[0], ring.at.point[1]);
        let (hw, r) = (ring.half_width + 2.0, RING + 2.0);
        let boxed = |cx: f64, cy: f64| -> Rect { [cx - hw, cy - r, cx + hw, cy + r] };
        let spots = std::iter::once((x, y)).chain((1..=4).flat_map(|step| {
            let d = step as f64 * (2.0 * hw.max(r) + 4.0);
            let n = 6 * step;
            (0..n).map(move |k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64 - std::f64::consts::FRAC_PI_4;
                (x + d * a.cos(), y - d * a.sin())
            })
        }));
        let mut chosen = (x, y);
        for (cx, cy) in spots {
            if placer.free(&boxed(cx, cy)) {
                chosen = (cx, cy);
                break;
            }
        }
        placer.take(boxed(chosen.0, chosen.1));
        out.push(chosen);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::model::Model;
    use super::super::picture::picture;
    use super::*;

    /// The rounds that collided at one place share one ring, numbered with each of them;
    /// a collision elsewhere keeps its own.
    #[test]
    fn rings_of_one_place_are_merged_with_their_rounds() {
        let mark = |round: usize, point: [f64; 2]| Mark {
            round: Some(round),
            time: round as f64,
            bodies: ["R1".into(), "R2".into()],
            point,
        };
        let square = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let model = Model {
            title: "rings".into(),
            verdict: String::new(),
            end: 1.0,
            delta: 0.01,
            robots: Vec::new(),
            obstacles: vec![square],
            obstacle_names: Vec::new(),
            tasks: Vec::new(),
            rounds: vec![
                mark(1, [2.0, 2.0]),
                mark(2, [8.0, 8.0]),
                mark(3, [2.0, 2.0 + 1e-6]),
                mark(4, [2.0, 2.0]),
            ],
            contact: None,
            safe_until: None,
        };
        let frame = Frame::of(&model);
        let marks: Vec<&Mark> = model.rounds.iter().collect();
        let rings = rings_of(&marks, &frame);
        let numbers: Vec<&str> = rings.iter().map(|r| r.numbers.as_str()).collect();
        assert_eq!(numbers, ["1, 3, 4", "2"]);
        assert!(rings[0].half_width > RING && rings[1].half_width == RING);
        let svg = picture(&model);
        assert!(svg.contains("1, 3, 4") && svg.contains(">\n2\n<"), "{svg}");
    }
}
