//! Bad `[engines.rapier]` options: each gives one located message naming the field and
//! the valid range, and the settings every run records are the ones it ran with.

use std::path::Path;

use rockslide::case::parse_case;
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;
use rockslide::engine::rigid_body::variant as rapier_variant;

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
    let c = crate::common::parse_with_bad_options(Path::new("opts.toml"), &text);
    let errors = Rapier.parse_options(&c).err().unwrap_or_default();
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
    assert!(
        Rapier
            .parse_options(&c)
            .err()
            .unwrap_or_default()
            .is_empty()
    );
    let run = Rapier.run(&c, rapier_variant::FIXED_GROUND, 0.01).unwrap();
    let get = |k: &str| crate::common::setting(&run, k).unwrap_or_default();
    assert_eq!(get("dt"), "0.01");
    assert_eq!(get("substeps"), "16");
    assert_eq!(get("solver iterations"), "3");
    assert_eq!(get("contact softness (fixed body)"), "120, 10");
    assert!(get("friction model").starts_with("Simplified"));
    assert_eq!(run.stats.steps, 250);
    assert_eq!(run.stats.substeps_per_step, Some(16));
}

/// `step_rule = "none"` (what the stability map runs) makes rapier take exactly one step
/// per output step, and says so; `contact_model = rapier_variant::APPLIED_FORCE` on a scene that is not
/// a rocking body is a located error; a bad `step_rule` lists the valid ones.
#[test]
fn step_rule_none_steps_once_per_output_step() {
    let c = with_options("step_rule = \"none\"");
    let dt = 2e-3;
    let run = Rapier.run(&c, rapier_variant::FIXED_GROUND, dt).unwrap();
    let n = rockslide::engine::step_count(c.run.duration, dt) as u64;
    assert_eq!(run.stats.steps, n, "one rapier step per output step");
    let ruled = Rapier
        .run(&with_options(""), rapier_variant::FIXED_GROUND, dt)
        .unwrap();
    assert_eq!(
        ruled.stats.steps, n,
        "the block's rule divides only record runs"
    );
    let osc = std::fs::read_to_string("cases/pepo-mass-accel.toml").unwrap();
    let with = |o: &str| {
        let t = osc.replacen("[engines.rapier]", &format!("[engines.rapier]\n{o}"), 1);
        parse_case(Path::new("pepo.toml"), &t).unwrap()
    };
    let none = Rapier
        .run(
            &with("step_rule = \"none\""),
            rapier_variant::APPLIED_FORCE,
            5e-3,
        )
        .unwrap();
    let rule = Rapier
        .run(&with(""), rapier_variant::APPLIED_FORCE, 5e-3)
        .unwrap();
    assert_eq!(
        rule.stats.steps,
        5 * none.stats.steps,
        "the rule: 1 ms steps under 5 ms"
    );
    assert!(
        none.findings
            .iter()
            .any(|f| f.starts_with("outside the engine's validity") && f.contains("step_rule")),
        "{:?}",
        none.findings
    );
    let bad = |o: &str| {
        let t = osc.replacen("[engines.rapier]", &format!("[engines.rapier]\n{o}"), 1);
        crate::common::parse_with_bad_options(Path::new("pepo.toml"), &t)
    };
    let errors = Rapier
        .parse_options(&bad("contact_model = \"applied-force\""))
        .unwrap_err();
    assert_eq!(errors.len(), 1);
    assert!(errors[0].to_string().contains("rocking body only"));
    let errors = Rapier
        .parse_options(&bad("step_rule = \"sometimes\""))
        .unwrap_err();
    assert_eq!(errors.len(), 1);
    assert!(errors[0].to_string().contains("\"none\""), "{}", errors[0]);
}

/// The computed supports' former name, `contact_model = "applied-force"` (also the name of
/// the mass-acceleration variant), is still read as `"computed-supports"`: the same run bit
/// for bit, with a note located at the field among its findings.
#[test]
fn the_former_contact_model_name_is_read_with_a_located_note() {
    let rpepo = std::fs::read_to_string("cases/rpepo-mass-accel.toml").unwrap();
    let section = rpepo
        .lines()
        .position(|l| l.starts_with("[engines.rapier]"))
        .expect("the case has a rapier section");
    let with = |name: &str| {
        let option = format!("[engines.rapier]\ncontact_model = \"{name}\"");
        let text = rpepo.replacen("[engines.rapier]", &option, 1);
        let mut c = parse_case(Path::new("rpepo.toml"), &text).unwrap();
        c.run.duration = 0.2;
        c
    };
    let variant = rapier_variant::APPLIED_FORCE;
    let former = Rapier.run(&with("applied-force"), variant, 1e-3).unwrap();
    let now = Rapier
        .run(&with("computed-supports"), variant, 1e-3)
        .unwrap();
    assert!(now.status.completed(), "{}", now.status);
    assert_eq!(former.trace.columns.len(), now.trace.columns.len());
    for (a, b) in former.trace.columns.iter().zip(&now.trace.columns) {
        let bits = |c: &[f64]| c.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(a), bits(b));
    }
    let located = format!(
        "rpepo.toml:{}:17: engines.rapier.contact_model: \"applied-force\" is the former name of \"computed-supports\"",
        section + 2
    );
    assert!(
        former.findings[0].starts_with(&located),
        "{:?}",
        former.findings
    );
    assert_eq!(former.findings[1..], now.findings[..]);
    assert_eq!(
        crate::common::setting(&former, "contact model"),
        crate::common::setting(&now, "contact model")
    );
}
