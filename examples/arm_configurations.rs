//! What choosing each arm's configuration at each task buys (issue 22, item 3): generated
//! SCARA cells sequenced collision-blind with every arm in its first configuration (elbow up
//! where the limits allow), in the one it reaches soonest from home, and in the ones chosen
//! along the routes.
//!
//! `cargo run --release --example arm_configurations -- [ARMS TASKS COUNT]` (default 4 40 6)

use workcell::cell::parse_cell;
use workcell::generate::{generate_scara_cell, ScaraRequest};
use workcell::wcp::{prepare, sequence, ConfigurationChoice, SolveOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let (arms, tasks, count) = match args[..] {
        [a, t, c] => (a, t, c),
        _ => (4, 40, 6),
    };
    println!("cell\tfirst\tnearest-home\tchosen\tgain over first %\tover nearest-home %");
    for k in 0..count as u64 {
        let req = ScaraRequest { arms, tasks };
        let doc = generate_scara_cell(&req, 1, k)?;
        let cell = parse_cell(&doc.to_string(), format!("scara-{k}").as_ref())?.cell;
        let with = |configurations| SolveOptions {
            configurations,
            ..SolveOptions::default()
        };
        let blind = |opts: &SolveOptions| -> Result<f64, Box<dyn std::error::Error>> {
            let prepared = prepare(&cell, opts, &())?;
            let prepared = workcell::wcp::choose_configurations(&cell, &prepared, opts, &())?
                .unwrap_or(prepared);
            Ok(sequence(&cell, &prepared, &[], opts)?.makespan)
        };
        let first = blind(&with(ConfigurationChoice::First))?;
        let near = blind(&with(ConfigurationChoice::NearestHome))?;
        let chosen = blind(&with(ConfigurationChoice::Chosen))?;
        let gain = |m: f64| 100.0 * (m - chosen) / m;
        println!(
            "{k}\t{first:.3}\t{near:.3}\t{chosen:.3}\t{:.2}\t{:.2}",
            gain(first),
            gain(near)
        );
    }
    Ok(())
}
