//! Bad `[engines.rapier]` options: each gives one located message naming the field and
//! the valid range, and the settings every run records are the ones it ran with.

use std::path::Path;

use rockslide::case::parse_case;
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;

fn with_options(options: &str) -> rockslide::case::Case {
    let text = std::fs::read_to_string("cases/housner-free-rocking.toml")
        .unwrap()
        .replace("[engines.rapier]", &format!("[engines.rapier]\n{options}"));
    parse_case(Path::new("opts.toml"), &text).expect("parses")
}

#[test]
fn bad_options_are_located_errors() {
    let text = std::fs::read_to_string("cases/housner-free-rocking.toml")
        .unwrap()
        .replace("substeps = 16", "substeps = 0")
        .replace(
            "[engines.rapier]",
            "[engines.rapier]\nfriction_model = \"sticky\"\nfoot_mass = 3.0\npgs_iterations = 2.5",
        );
    let c = parse_case(Path::new("opts.toml"), &text).expect("parses");
    let errors = Rapier.check_options(&c);
    let text: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
    println!("{text:#?}");
    assert_eq!(errors.len(), 4, "{text:?}");
    assert!(
        text.iter()
            .any(|t| t.contains("engines.rapier.substeps") && t.contains("from 1 to 1000"))
    );
    assert!(
        text.iter()
            .any(|t| t.contains("engines.rapier.friction_model") && t.contains("\"simplified\""))
    );
    assert!(
        text.iter()
            .any(|t| t.contains("engines.rapier.foot_mass") && t.contains("unknown option"))
    );
    assert!(
        text.iter()
            .any(|t| t.contains("engines.rapier.pgs_iterations") && t.contains("whole number"))
    );
    // located: file:line:col
    assert!(text.iter().all(|t| t.starts_with("opts.toml:")), "{text:?}");
}

#[test]
fn runs_record_their_settings() {
    let c = with_options("contact_hz = 120.0\npgs_iterations = 3");
    assert!(Rapier.check_options(&c).is_empty());
    let run = Rapier.run(&c, "fixed-ground", 0.01).unwrap();
    let get = |k: &str| {
        run.settings
            .iter()
            .find(|(n, _)| n.starts_with(k))
            .map(|(_, v)| v.clone())
            .unwrap_or_default()
    };
    assert_eq!(get("dt"), "0.01");
    assert_eq!(get("substeps"), "16");
    assert_eq!(get("solver iterations"), "3");
    assert_eq!(get("contact softness (fixed body)"), "120, 10");
    assert!(get("friction model").starts_with("Simplified"));
    assert_eq!(run.stats.steps, 250);
    assert_eq!(run.stats.substeps_per_step, Some(16));
}
