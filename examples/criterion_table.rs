//! Prints criterion's medians as a Markdown table, the way the README shows them:
//!
//! ```sh
//! cargo run --release --example criterion_table -- GROUP [--per K] [--ratio A/B]... [--transpose]
//! ```
//!
//! Reads every `<target>/criterion/**/new/{benchmark,estimates}.json` whose id starts with
//! `GROUP` (e.g. `distance`, `methods/`, `hall-`, `check`; `CARGO_TARGET_DIR` or `target`).
//! `GROUP` is left out of the ids when a `/` follows it; then an id `a/b/c` goes to row
//! `a/b`, column `c`, and an id `a` to row `a`, column `median`. `--per K` divides every median by K (a bench
//! that times K queries per iteration); each `--ratio A/B` adds the row or column A over B;
//! `--transpose` swaps rows and columns. It warns when the figures were written more than an
//! hour apart, as stale results of criterion's earlier runs would be.

use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

struct Args {
    group: String,
    per: f64,
    ratios: Vec<(String, String)>,
    transpose: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        group: String::new(),
        per: 1.0,
        ratios: Vec::new(),
        transpose: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--per" => {
                let k = it.next().ok_or("--per needs a number")?;
                args.per = k.parse().map_err(|_| format!("--per {k}: not a number"))?;
            }
            "--ratio" => {
                let r = it.next().ok_or("--ratio needs A/B")?;
                let (a, b) = r.rsplit_once('/').ok_or(format!("--ratio {r}: not A/B"))?;
                args.ratios.push((a.to_string(), b.to_string()));
            }
            "--transpose" => args.transpose = true,
            _ if args.group.is_empty() => args.group = a,
            _ => return Err(format!("unexpected argument {a}")),
        }
    }
    if args.group.is_empty() {
        return Err("usage: criterion_table GROUP [--per K] [--ratio A/B]... [--transpose]".into());
    }
    Ok(args)
}

/// Every `new` folder under `dir` that holds both files.
fn runs(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n == "new") {
                if p.join("benchmark.json").is_file() && p.join("estimates.json").is_file() {
                    out.push(p);
                }
            } else {
                runs(&p, out);
            }
        }
    }
}

fn read(path: &Path) -> Result<Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// A time in nanoseconds, to 3 significant digits in a fitting unit.
fn time(ns: f64) -> String {
    // Rounded first, so that 999.7 ns reads 1.00 µs, not 1000 ns.
    let ns = if ns > 0.0 {
        let scale = 10f64.powi(ns.log10().floor() as i32 - 2);
        (ns / scale).round() * scale
    } else {
        ns
    };
    let (v, unit) = match ns {
        x if x < 1e3 => (x, "ns"),
        x if x < 1e6 => (x / 1e3, "µs"),
        x if x < 1e9 => (x / 1e6, "ms"),
        x => (x / 1e9, "s"),
    };
    let decimals = if v < 10.0 {
        2
    } else if v < 100.0 {
        1
    } else {
        0
    };
    format!("{v:.decimals$} {unit}")
}

fn main() {
    if let Err(e) = run() {
        eprintln!("criterion_table: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or("target".into(), PathBuf::from);
    let mut found = Vec::new();
    runs(&target.join("criterion"), &mut found);
    // (row, column) -> median in ns.
    let mut cells = BTreeMap::new();
    let (mut rows, mut cols) = (Vec::new(), Vec::new());
    // The oldest and the newest of the figures: criterion keeps the results of benchmarks
    // that no longer exist, and of runs long past.
    let mut when = None;
    for dir in found {
        let id = read(&dir.join("benchmark.json"))?["full_id"]
            .as_str()
            .ok_or(format!("{}: no full_id", dir.display()))?
            .to_string();
        if !id.starts_with(&args.group) {
            continue;
        }
        let modified = std::fs::metadata(dir.join("estimates.json"))
            .and_then(|m| m.modified())
            .map_err(|e| format!("{}: {e}", dir.display()))?;
        when = Some(
            when.map_or((modified, modified), |(a, b): (SystemTime, SystemTime)| {
                (a.min(modified), b.max(modified))
            }),
        );
        let median = read(&dir.join("estimates.json"))?["median"]["point_estimate"]
            .as_f64()
            .ok_or(format!("{}: no median", dir.display()))?;
        // The group's own name, when it ends at a `/`, says nothing in the table.
        let rest = id[args.group.len()..].strip_prefix('/');
        let short = match rest {
            Some(rest) => rest,
            None if args.group.ends_with('/') => &id[args.group.len()..],
            None => &id,
        };
        let (row, col) = short.rsplit_once('/').unwrap_or((short, "median"));
        let (row, col) = if args.transpose {
            (col, row)
        } else {
            (row, col)
        };
        for (name, list) in [(row, &mut rows), (col, &mut cols)] {
            if !list.iter().any(|n| n == name) {
                list.push(name.to_string());
            }
        }
        cells.insert((row.to_string(), col.to_string()), median / args.per);
    }
    if let Some((oldest, newest)) = when {
        let spread = newest.duration_since(oldest).unwrap_or_default();
        if spread > Duration::from_secs(3600) {
            eprintln!(
                "criterion_table: these figures were written up to {:.1} hours apart: \
                 some may be stale (delete target/criterion and run the bench again)",
                spread.as_secs_f64() / 3600.0
            );
        }
    }
    if cells.is_empty() {
        return Err(format!(
            "no benchmark under {} starts with {}: run cargo bench first",
            target.join("criterion").display(),
            args.group
        ));
    }
    // Numbers sort as numbers (4, 8, 16, 64; hall-10 before hall-100), the rest by name.
    let key = |s: &String| {
        let digits: String = s.chars().filter(char::is_ascii_digit).collect();
        let stem: String = s.chars().filter(|c| !c.is_ascii_digit()).collect();
        (stem, digits.parse::<u64>().unwrap_or(0), s.clone())
    };
    rows.sort_by_key(key);
    cols.sort_by_key(key);
    let ratio = |r: &str, c: &str, (a, b): &(String, String), by_col: bool| {
        let get = |x: &str| {
            let k = if by_col { (r, x) } else { (x, c) };
            cells.get(&(k.0.to_string(), k.1.to_string())).copied()
        };
        match (get(a), get(b)) {
            (Some(x), Some(y)) => format!("{:.3}", x / y),
            _ => "-".into(),
        }
    };
    let (mut ratio_of_cols, mut ratio_of_rows) = (Vec::new(), Vec::new());
    for (a, b) in &args.ratios {
        if cols.contains(a) && cols.contains(b) {
            ratio_of_cols.push((a.clone(), b.clone()));
        } else if rows.contains(a) && rows.contains(b) {
            ratio_of_rows.push((a.clone(), b.clone()));
        } else {
            return Err(format!(
                "--ratio {a}/{b}: both must be rows or both columns"
            ));
        }
    }
    let mut header = vec![String::new()];
    header.extend(cols.iter().cloned());
    header.extend(ratio_of_cols.iter().map(|(a, b)| format!("{a} / {b}")));
    println!("| {} |", header.join(" | "));
    println!("|{}", " --- |".repeat(header.len()));
    for r in &rows {
        let mut line = vec![r.clone()];
        for c in &cols {
            line.push(
                cells
                    .get(&(r.clone(), c.clone()))
                    .map_or("-".into(), |&v| time(v)),
            );
        }
        line.extend(ratio_of_cols.iter().map(|q| ratio(r, "", q, true)));
        println!("| {} |", line.join(" | "));
    }
    for q in &ratio_of_rows {
        let mut line = vec![format!("{} / {}", q.0, q.1)];
        line.extend(cols.iter().map(|c| ratio("", c, q, false)));
        println!("| {} |", line.join(" | "));
    }
    Ok(())
}
