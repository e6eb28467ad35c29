//! Bidirectional (3D) scenes (docs/bidirectional.md): the keys read into `Scene::spatial`, their
//! located errors, a planar case left planar, and every 2D engine refusing a 3D scene
//! through the registry's one gate (never a silent planar run).

use crate::common::{case, repo};
use rockslide::case::{Case, Signal, parse_case};
use rockslide::engine::predictor_corrector::variant as pc_variant;

/// The shipped PEPO (mass acceleration) with `extra` appended to `[excitation]` and the
/// double arrangement dropped (its text is kept otherwise).
fn pepo_with(excitation_extra: &str, tail: &str) -> Result<Case, String> {
    let path = repo("cases/pepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text.replace(
        "cycles = 0.5\n",
        &format!("cycles = 0.5\n{excitation_extra}\n"),
    ) + tail;
    parse_case(&path, &text).map_err(|e| e.to_string())
}

#[test]
fn a_planar_case_stays_planar() {
    assert!(case("pepo-mass-accel").scene.spatial.is_none());
    assert!(case("records/block-northridge").scene.spatial.is_none());
}

#[test]
fn azimuth_and_second_component_are_read() {
    let c = pepo_with(
        "azimuth_deg = 30.0",
        "\n[excitation.y]\nshape = \"sine-pulse\"\namplitude = 0.5\nomega = 10.0\ncycles = 1.0\n",
    )
    .unwrap();
    let s = c.scene.spatial.as_ref().expect("a 3D scene");
    assert_eq!(s.azimuth_deg, 30.0);
    assert_eq!(
        s.second,
        Some(Signal::SinePulse {
            amplitude: 0.5,
            omega: 10.0,
            cycles: 1.0
        })
    );
    assert!(s.depth.is_none() && s.inertia.is_none());
    let [c1, s1] = s.first_direction();
    assert_eq!(
        [c1, s1],
        [30f64.to_radians().cos(), 30f64.to_radians().sin()]
    );
}

#[test]
fn bad_spatial_keys_are_located_errors() {
    let errs = pepo_with(
        "azimuth_deg = 400.0",
        "\n[excitation.y]\nshape = \"square\"\namplitude = 0.5\n",
    )
    .unwrap_err();
    println!("{errs}");
    assert!(
        errs.contains("excitation.azimuth_deg: is 400, but must be between -360 and 360"),
        "{errs}"
    );
    assert!(
        errs.contains("excitation.y.shape: is \"square\", but must be \"sine-pulse\""),
        "{errs}"
    );
    // line and column of the azimuth (the line after `cycles = 0.5` of the excitation)
    let line = std::fs::read_to_string(repo("cases/pepo-mass-accel.toml"))
        .unwrap()
        .lines()
        .position(|l| l.starts_with("cycles = 0.5"))
        .unwrap()
        + 2;
    assert!(
        errs.contains(&format!(":{line}:15: excitation.azimuth_deg")),
        "{errs}"
    );
    // a point mass has no depth
    let errs = pepo_with("azimuth_deg = 0.0", "").unwrap();
    assert!(errs.scene.spatial.is_some());
    let path = repo("cases/pepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("gravity = 1.0 ", "half_depth = 1.0\ngravity = 1.0 ");
    let errs = parse_case(&path, &text).unwrap_err().to_string();
    assert!(
        errs.contains("model.half_depth: does not apply to a model of kind \"oscillator\""),
        "{errs}"
    );
}

#[test]
fn a_body_in_a_3d_scene_needs_its_depth() {
    let path = repo("cases/rpepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let spatial = text.replace("[excitation]\n", "[excitation]\nazimuth_deg = 10.0\n");
    let errs = parse_case(&path, &spatial).unwrap_err().to_string();
    assert!(
        errs.contains("model.half_depth: is required")
            && errs.contains("model.support_rows: is required"),
        "{errs}"
    );
    let with_depth = spatial.replace(
        "[model]\n",
        "[model]\nhalf_depth = 1.5\nsupport_rows = 3\nrotational_inertia_x = 1.0\nrotational_inertia_y = 2.0\nrotational_inertia_z = 3.0\n",
    );
    let errs = parse_case(&path, &with_depth).unwrap_err().to_string();
    assert!(
        errs.contains(
            ":36:22: model.rotational_inertia: is 21.354166666666668, but rotational_inertia_y is 2"
        ),
        "{errs}"
    );
    let with_depth = with_depth.replace(
        "rotational_inertia_y = 2.0",
        "rotational_inertia_y = 21.354166666666668",
    );
    let c = parse_case(&path, &with_depth).unwrap();
    let s = c.scene.spatial.unwrap();
    let d = s.depth.unwrap();
    assert_eq!((d.half_depth, d.support_rows), (1.5, 3));
    assert_eq!(d.row_positions(), vec![-1.5, 0.0, 1.5]);
    assert_eq!(s.inertia, Some([1.0, 21.354166666666668, 3.0]));
    let partial = spatial.replace(
        "[model]\n",
        "[model]\nhalf_depth = 1.5\nsupport_rows = 0\nrotational_inertia_x = 1.0\n",
    );
    let errs = parse_case(&path, &partial).unwrap_err().to_string();
    assert!(
        errs.contains("model.support_rows: is 0, but must be at least 1"),
        "{errs}"
    );
    assert!(
        errs.contains("model.rotational_inertia_y: is required with the other"),
        "{errs}"
    );
}

#[test]
fn every_2d_engine_refuses_a_3d_scene() {
    let c = pepo_with("azimuth_deg = 30.0", "").unwrap();
    // fe and rapier model plan motion (tests/all/fe_space.rs, tests/all/rapier_space.rs);
    // the others do not.
    let planar_only: Vec<_> = rockslide::engine::all()
        .into_iter()
        .filter(|e| !e.models_plan_motion())
        .collect();
    let ids: Vec<_> = planar_only.iter().map(|e| e.id()).collect();
    assert_eq!(ids, ["predictor-corrector"]);
    for engine in planar_only {
        assert_eq!(
            engine.variants(&c.scene).unwrap_err().0,
            format!(
                "bidirectional (3D) scene is not modelled in {}",
                engine.id()
            )
        );
        let err = engine
            .run(&c, pc_variant::PAPER, 0.01)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("bidirectional (3D) scene is not modelled"),
            "{err}"
        );
    }
    // the same engines still run the planar case
    let planar = case("pepo-mass-accel");
    for engine in rockslide::engine::all() {
        assert!(engine.variants(&planar.scene).is_ok());
    }
}

#[test]
fn the_spatial_cases_load_and_select_the_plan_references() {
    for (name, method) in [
        ("spatial/pepo-pulse-azimuth30", "circular yield surface"),
        (
            "spatial/two-station/block-record-pair",
            "isotropic friction cone",
        ),
    ] {
        let c = case(name);
        assert!(c.scene.spatial.is_some());
        let r = rockslide::reference::for_case(&c).unwrap();
        assert!(r.method().contains(method), "{}", r.method());
        // fe models plan motion (a rigid block it refuses: no contact stiffness), rapier
        // runs both
        for engine in rockslide::engine::all() {
            let runs = match engine.id() {
                "fe" => name.contains("pepo"),
                "rapier" => true,
                _ => false,
            };
            assert_eq!(engine.variants(&c.scene).is_ok(), runs, "{}", engine.id());
        }
    }
    // the pair's peak resultant sliding as measured (docs/bidirectional.md)
    let c = case("spatial/two-station/block-record-pair");
    let r = rockslide::reference::for_case(&c).unwrap();
    let peak = r
        .exact_quantities()
        .into_iter()
        .find(|(k, _)| *k == "peak_resultant_sliding")
        .unwrap()
        .1;
    assert!((peak - 3.2167e-2).abs() < 5e-5, "{peak}");
}
