//! `workcell compare`: the table, the JSON and the chart, the methods' known weaknesses shown,
//! and the parry peer's independent cross-check of the default method on every generated kind.

#[cfg(feature = "cli")]
use crate::common::{temp_dir_made, workcell};
#[cfg(feature = "cli")]
use std::path::{Path, PathBuf};
use workcell::collision::Method;
use workcell::compare::{compare, Comparison, Contender, NamedScene};
use workcell::generate::{generate_scene, Kind};

#[cfg(feature = "cli")]
fn cells() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("cells")
}

fn method<'c>(c: &'c Comparison, name: &str) -> &'c workcell::compare::MethodSummary {
    c.methods.iter().find(|m| m.method == name).unwrap()
}

#[cfg(feature = "cli")]
#[test]
fn shipped_scenes_give_json_and_a_chart() {
    let svg = temp_dir_made("compare", "chart").join("chart.svg");
    let o = workcell(&[
        "compare",
        cells().to_str().unwrap(),
        "--json",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // The seven scenes of cells/, the `*-cell.json` cells aside.
    assert_eq!(json["scenes"], 7);
    let methods = json["methods"].as_array().unwrap();
    let names: Vec<&str> = methods
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    let mut expected = vec![
        "adaptive",
        "adaptive-paper",
        "advance",
        "sampled:1",
        "sampled:0.1",
        "sampled:0.01",
        "sampled:0.001",
    ];
    if cfg!(feature = "parry-peer") {
        expected.push("parry");
    }
    assert_eq!(names, expected);
    for m in methods {
        assert!(m["median_us"].as_f64().unwrap() > 0.0, "{m}");
        for key in ["missed", "invented", "max_time_error"] {
            assert!(m.get(key).is_some(), "{m} has no {key}");
        }
    }
    let adaptive = &methods[0];
    assert_eq!(
        (adaptive["missed"].as_u64(), adaptive["invented"].as_u64()),
        (Some(0), Some(0))
    );
    // bad-velocities.json fools the paper's bound; tunnelling.json passes between samples.
    assert!(methods[1]["missed"].as_u64().unwrap() >= 1);
    assert!(methods[3]["missed"].as_u64().unwrap() >= 1);
    let chart = std::fs::read_to_string(&svg).unwrap();
    assert!(chart.starts_with("<svg") && chart.contains("sampled:0.01"));
}

#[cfg(feature = "cli")]
#[test]
fn the_table_lists_every_method_asked_for() {
    let o = workcell(&[
        "compare",
        cells().join("tunnelling.json").to_str().unwrap(),
        "--methods",
        "adaptive,sampled:0.5",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let table = String::from_utf8(o.stdout).unwrap();
    assert!(table.starts_with("1 scene, 1 colliding"), "{table}");
    assert!(table.contains("| adaptive | "), "{table}");
    assert!(table.contains("| sampled:0.5 | "), "{table}");
}

#[cfg(feature = "cli")]
#[test]
fn bad_input_exits_2_naming_the_file() {
    let dir = temp_dir_made("compare", "bad");
    std::fs::write(dir.join("broken.json"), "{\"robots\": [}").unwrap();
    let o = workcell(&["compare", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("broken.json"));
    let empty = temp_dir_made("compare", "empty");
    let o = workcell(&["compare", empty.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no scene files"));
    let o = workcell(&[
        "compare",
        cells().to_str().unwrap(),
        "--methods",
        "adaptive,bisect",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown method `bisect`"));
}

/// Five scenes of every generated kind (halls of 12 robots).
fn generated() -> Vec<NamedScene> {
    Kind::ALL
        .iter()
        .flat_map(|&kind| {
            (0..5).map(move |k| NamedScene {
                name: format!("{}-{k}", kind.name()),
                scene: generate_scene(kind, 7, k, 12),
            })
        })
        .collect()
}

#[test]
fn the_weak_methods_fail_where_they_are_expected_to() {
    let scenes = generated();
    let contenders = [
        Contender::Ours(Method::DEFAULT),
        Contender::Ours("adaptive-paper".parse().unwrap()),
        Contender::Ours(Method::Advance),
        Contender::Ours(Method::Sampled { step: 1.0 }),
    ];
    let c = compare(&scenes, &contenders, |_| {});
    assert!(c.colliding > 0 && c.colliding < c.scenes);
    for name in ["adaptive", "advance"] {
        let m = method(&c, name);
        assert_eq!((m.missed, m.invented), (0, 0), "{name}");
    }
    // Tunnelling scenes pass between samples a whole time unit apart.
    assert!(method(&c, "sampled:1").missed >= 1);
    // No method invents: every contact reported has an exact witness closer than δ.
    assert!(c.methods.iter().all(|m| m.invented == 0));
}

/// The independent cross-check: parry's time of impact agrees with the reference on every
/// generated kind of rigid bodies, so `adaptive` missing and inventing nothing is not judged
/// by itself alone. parry has no motion for a linkage: it counts every arm scene unsupported
/// (the arms' own cross-check is the reference of `tests/integration/arms.rs`).
#[cfg(feature = "parry-peer")]
#[test]
fn parry_agrees_with_the_reference_on_every_kind() {
    let (arms, rigid): (Vec<NamedScene>, Vec<NamedScene>) = generated()
        .into_iter()
        .partition(|s| s.scene.bodies.iter().any(|b| b.link().is_some()));
    let contenders = [Contender::Ours(Method::DEFAULT), Contender::Parry];
    let c = compare(&rigid, &contenders, |_| {});
    assert!(c.disagreements.is_empty(), "{:#?}", c.disagreements);
    let parry = method(&c, "parry");
    assert_eq!((parry.missed, parry.invented, parry.unsupported), (0, 0, 0));
    let adaptive = method(&c, "adaptive");
    assert_eq!((adaptive.missed, adaptive.invented), (0, 0));
    assert_eq!(arms.len(), 5 * Kind::ARMS.len());
    let c = compare(&arms, &contenders, |_| {});
    // Unsupported wherever parry had a link pair to cast (a scene decided at its start
    // leaves none).
    let unsupported = method(&c, "parry").unsupported;
    assert!(
        2 * unsupported >= arms.len(),
        "{unsupported} of {}",
        arms.len()
    );
    let adaptive = method(&c, "adaptive");
    assert_eq!((adaptive.missed, adaptive.invented), (0, 0));
}
