//! Draws `docs/img/foxglove-layout.svg`: what a user sees after opening a rockslide MCAP
//! trace in Foxglove with a 3D panel and a Plot panel (docs/traces.md).
//!
//! Everything drawn is read back from MCAP files rockslide writes (with the `mcap` crate):
//! - the Plot panel: the message paths `/predictor-corrector/paper/state.rel_disp` and
//!   `/reference/state.rel_disp` (and `.slide`) of the PEPO mass-acceleration case;
//! - the 3D panel, seen from the side (−y, orthographic): the ground slab, the body's box,
//!   supports and centre of mass placed by the `foxglove_msgs/msg/FrameTransforms` messages, and the
//!   force arrows of `foxglove_msgs/msg/SceneUpdate`, at four instants (a strobe), for a synthetic
//!   rocking motion on the RPEPO geometry (no rocking engine is needed for the picture).
//!
//! It is an illustration, not a screenshot of Foxglove. Run:
//! `cargo run --example trace_picture [out.svg]`.

use std::error::Error;
use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use rockslide::analysis::responses;
use rockslide::case::{load_case, parse_case};
use rockslide::engine::{Run, RunStatus};
use rockslide::formats::{mcap_bytes, read_mcap, scene3d};
use rockslide::report::{case_trace_log, write_case_outputs};
use rockslide::suite::{CaseResult, run_case};
use rockslide::trace::{Trace, q};
use serde_json::Value;

const RPEPO: &str = r#"
title = "RPEPO geometry (illustration)"
source = "AL-Shawaf & Rahman, Fig. 3"
requirement = "picture only"
[model]
kind = "rocking-body"
mass = 1.0e6
gravity = 9.81
cm_height = 0.625
half_width = 0.5
supports = 10
[model.contact]
kx = 2.4e9
kz = 3.94784e8
mu = 0.5
[excitation]
kind = "none"
[run]
duration = 2.0
dt = 0.001
"#;

const BG: RGBColor = RGBColor(24, 24, 30);
const PANEL: RGBColor = RGBColor(32, 33, 40);
const FG: RGBColor = RGBColor(220, 220, 228);
const DIM: RGBColor = RGBColor(120, 122, 135);

/// A synthetic rocking motion: the body rocks on its right then its left corner
/// (θ = 0.12 sin 2πt/0.8), the ground moves xg = 0.15 sin 2πt/2.
fn rocking_trace() -> Trace {
    let (b, h, w) = (0.5, 0.625, 1.0e6 * 9.81);
    let chans = [
        &q::GROUND_DISP,
        &q::CM_X,
        &q::CM_Z,
        &q::ROTATION,
        &q::BASE_SHEAR,
        &q::NORMAL,
    ];
    let mut tr = Trace::with_channels(&chans, 2001);
    for i in 0..=2000 {
        let t = i as f64 * 1e-3;
        let th: f64 = 0.12 * (2.0 * std::f64::consts::PI * t / 0.8).sin();
        let pivot = if th < 0.0 { b } else { -b }; // clockwise: right corner
        let (rx, rz) = (-pivot, h); // CM relative to the pivot, rotated by θ
        let cx = pivot + rx * th.cos() - rz * th.sin();
        let cz = rx * th.sin() + rz * th.cos();
        let xg = 0.15 * (std::f64::consts::PI * t).sin();
        tr.push(t, &[xg, cx, cz - h, th, -0.3 * w * th / 0.12, w]);
    }
    tr
}

/// Rotate p by the quaternion of a transform message and translate.
fn apply(tf: &Value, p: [f64; 3]) -> [f64; 3] {
    let f = |v: &Value, k: &str| v[k].as_f64().unwrap();
    let (t, r) = (&tf["translation"], &tf["rotation"]);
    let (u, w) = ([f(r, "x"), f(r, "y"), f(r, "z")], f(r, "w"));
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let c1 = cross(u, p);
    let c2 = cross(u, c1);
    [
        p[0] + 2.0 * (w * c1[0] + c2[0]) + f(t, "x"),
        p[1] + 2.0 * (w * c1[1] + c2[1]) + f(t, "y"),
        p[2] + 2.0 * (w * c1[2] + c2[2]) + f(t, "z"),
    ]
}

fn color(v: &Value, alpha: f64) -> RGBAColor {
    let c = |k: &str| (v[k].as_f64().unwrap() * 255.0) as u8;
    RGBColor(c("r"), c("g"), c("b")).mix(alpha)
}

fn panel_header<DB: DrawingBackend>(area: &DrawingArea<DB, plotters::coord::Shift>, title: &str) {
    let (w, _) = area.dim_in_pixel();
    let _ = area.draw(&Rectangle::new([(0, 0), (w as i32, 26)], BG.filled()));
    let _ = area.draw(&Text::new(
        title.to_string(),
        (10, 6),
        ("sans-serif", 15).into_font().color(&FG),
    ));
}

/// The 3D messages of the synthetic rocking run: the scene, every frame transform and
/// every force update, each with its log time (ns).
struct RockMessages {
    scene: Value,
    transforms: Vec<(u64, Value)>,
    forces: Vec<(u64, Value)>,
}

/// The synthetic rocking trace as a case result, written as MCAP and read back message by
/// message.
fn rocking_messages() -> Result<RockMessages, Box<dyn Error>> {
    let rock_case = parse_case(Path::new("rpepo-illustration.toml"), RPEPO)?;
    let trace = rocking_trace();
    let run = Run {
        engine: "fe",
        variant: "exact".into(),
        arrangement: Default::default(),
        dt: 1e-3,
        settings: Vec::new(),
        stats: rockslide::engine::SolverStats::default(),
        findings: Vec::new(),
        trace: trace.clone(),
        status: RunStatus::Completed,
        wall_seconds: 0.0,
    };
    let rock = CaseResult {
        run_responses: vec![responses(&trace)],
        history_errors: vec![None],
        runs: vec![run],
        case: rock_case,
        not_applicable: Vec::new(),
        reference: Err("none".into()),
        checks: Vec::new(),
        invariants: Vec::new(),
        envelopes: Vec::new(),
        azimuths: None,
    };
    let bytes = mcap_bytes(&case_trace_log(&rock))?;
    let mut messages = RockMessages {
        scene: Value::Null,
        transforms: Vec::new(),
        forces: Vec::new(),
    };
    for m in mcap::MessageStream::new(&bytes)? {
        let m = m?;
        let schema = m.channel.schema.as_ref().map_or("", |s| s.name.as_str());
        let Some(ty) = scene3d::message_type(schema) else {
            continue; // the state, contacts and log: not drawn here
        };
        let v: Value = scene3d::decode(ty, &m.data)?;
        match m.channel.topic.as_str() {
            "/fe/exact/scene" => messages.scene = v,
            "/fe/exact/transform" => {
                let each = v["transforms"].as_array().cloned().unwrap_or_default();
                messages
                    .transforms
                    .extend(each.into_iter().map(|t| (m.log_time, t)));
            }
            "/fe/exact/forces" => messages.forces.push((m.log_time, v)),
            _ => {}
        }
    }
    Ok(messages)
}

/// The last message of `list` at or before `ns` (of frame `child`, when given).
fn at(list: &[(u64, Value)], ns: u64, child: Option<&str>) -> Value {
    list.iter()
        .rfind(|(t, v)| *t <= ns && child.is_none_or(|c| v["child_frame_id"] == c))
        .map(|(_, v)| v.clone())
        .unwrap()
}

/// The side view's chart: x and z in metres, equal scales.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The ground's and the body's transforms at one instant, and points of each frame in
/// the side view (x, z of the world).
struct Frames {
    ground: Value,
    body: Value,
}

impl Frames {
    fn at(rock: &RockMessages, ns: u64) -> Self {
        Self {
            ground: at(&rock.transforms, ns, Some("fe/exact/ground")),
            body: at(&rock.transforms, ns, Some("fe/exact/body")),
        }
    }

    fn ground(&self, p: [f64; 3]) -> (f64, f64) {
        let p = apply(&self.ground, p);
        (p[0], p[2])
    }

    fn body(&self, p: [f64; 3]) -> (f64, f64) {
        self.ground(apply(&self.body, p))
    }
}

/// The 3D panel, seen from the side: two earlier instants as outlines, then the current
/// one with the ground, the datum post and the force arrows.
fn draw_3d_panel(
    left: &DrawingArea<SVGBackend<'_>, Shift>,
    rock: &RockMessages,
) -> Result<(), Box<dyn Error>> {
    let view = left.margin(34, 8, 8, 8);
    let mut ch = ChartBuilder::on(&view)
        .x_label_area_size(34)
        .build_cartesian_2d(-1.2f64..1.2, -0.7f64..1.72)?; // equal scales
    ch.configure_mesh()
        .disable_mesh()
        .axis_style(DIM)
        .label_style(("sans-serif", 11).into_font().color(&DIM))
        .x_desc("x, m (side view from −y)")
        .draw()?;
    let snapshots = [0.4, 1.4, 1.0];
    for (k, &t) in snapshots.iter().enumerate() {
        let ns = (t * 1e9) as u64;
        let current = k == snapshots.len() - 1;
        let alpha = if current { 1.0 } else { 0.45 };
        let frames = Frames::at(rock, ns);
        if current {
            draw_ground(&mut ch, &rock.scene, &frames)?;
        }
        let top = draw_body(&mut ch, &rock.scene, &frames, current, alpha)?;
        if current {
            draw_forces(&mut ch, &at(&rock.forces, ns, None), &frames)?;
        }
        let cm = frames.body([0.0, 0.0, 0.0]);
        ch.draw_series(std::iter::once(Text::new(
            format!("t = {t} s"),
            (cm.0 - 0.1, top + 0.03 + 0.07 * k as f64),
            ("sans-serif", 12).into_font().color(&FG.mix(alpha)),
        )))?;
    }
    ch.draw_series(std::iter::once(Text::new(
        "outlines: earlier instants; arrows: total normal force (green) and shear (red) at O",
        (-1.15, -0.62),
        ("sans-serif", 12).into_font().color(&DIM),
    )))?;
    Ok(())
}

/// The scene's entity `id`.
fn entity<'a>(scene: &'a Value, id: &str) -> &'a Value {
    let ents = scene["entities"].as_array().unwrap();
    ents.iter().find(|e| e["id"] == id).unwrap()
}

/// The ground slab and its ticks (moving with the ground), and the datum post (world
/// frame).
fn draw_ground(
    ch: &mut Chart<'_, '_>,
    scene: &Value,
    frames: &Frames,
) -> Result<(), Box<dyn Error>> {
    for c in entity(scene, "ground")["cubes"].as_array().unwrap() {
        let (p, s) = (&c["pose"]["position"], &c["size"]);
        let f = |v: &Value, k: &str| v[k].as_f64().unwrap();
        let (x0, z0) = frames.ground([
            f(p, "x") - f(s, "x") / 2.0,
            0.0,
            f(p, "z") - f(s, "z") / 2.0,
        ]);
        let (x1, z1) = frames.ground([
            f(p, "x") + f(s, "x") / 2.0,
            0.0,
            f(p, "z") + f(s, "z") / 2.0,
        ]);
        // ticks lie flat on the slab: draw them into its edge so the side view shows them
        let (x0, x1, z0) = if f(s, "z") < 0.01 {
            (x0 - 0.004, x1 + 0.004, z0 - 0.035)
        } else {
            (x0, x1, z0)
        };
        ch.draw_series(std::iter::once(Rectangle::new(
            [(x0, z0), (x1, z1)],
            color(&c["color"], 1.0).filled(),
        )))?;
    }
    let d = &entity(scene, "datum")["cubes"][0];
    let hgt = d["size"]["z"].as_f64().unwrap();
    ch.draw_series(std::iter::once(Rectangle::new(
        [(-0.006, 0.0), (0.006, hgt)],
        color(&d["color"], 1.0).filled(),
    )))?;
    Ok(())
}

/// The body's box (filled at the current instant, an outline at the others), its
/// supports and centre of mass at the current one; returns the box's highest z.
fn draw_body(
    ch: &mut Chart<'_, '_>,
    scene: &Value,
    frames: &Frames,
    current: bool,
    alpha: f64,
) -> Result<f64, Box<dyn Error>> {
    let body = entity(scene, "body");
    let cube = &body["cubes"][0]["size"];
    let (sx, sz) = (
        cube["x"].as_f64().unwrap() / 2.0,
        cube["z"].as_f64().unwrap() / 2.0,
    );
    let corners: Vec<(f64, f64)> = [(-sx, -sz), (sx, -sz), (sx, sz), (-sx, sz)]
        .iter()
        .map(|&(x, z)| frames.body([x, 0.0, z]))
        .collect();
    let fill = color(&body["cubes"][0]["color"], 1.0);
    if current {
        ch.draw_series(std::iter::once(Polygon::new(
            corners.clone(),
            fill.mix(0.55).filled(),
        )))?;
    }
    let mut outline = corners.clone();
    outline.push(corners[0]);
    ch.draw_series(std::iter::once(PathElement::new(
        outline,
        fill.mix(alpha).stroke_width(2),
    )))?;
    for s in body["spheres"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|_| current)
    {
        let p = &s["pose"]["position"];
        let c = frames.body([p["x"].as_f64().unwrap(), 0.0, p["z"].as_f64().unwrap()]);
        ch.draw_series(std::iter::once(Circle::new(
            c,
            3,
            RGBColor(235, 235, 235).mix(alpha).filled(),
        )))?;
    }
    Ok(corners.iter().map(|c| c.1).fold(f64::MIN, f64::max))
}

/// The force arrows of one `SceneUpdate` (ground frame).
fn draw_forces(
    ch: &mut Chart<'_, '_>,
    forces: &Value,
    frames: &Frames,
) -> Result<(), Box<dyn Error>> {
    for a in forces["entities"][0]["arrows"].as_array().unwrap() {
        let len = a["shaft_length"].as_f64().unwrap() + a["head_length"].as_f64().unwrap();
        let frame = serde_json::json!({
            "translation": a["pose"]["position"], "rotation": a["pose"]["orientation"]
        });
        let tail = frames.ground(apply(&frame, [0.0, 0.0, 0.0]));
        let tip = frames.ground(apply(&frame, [len, 0.0, 0.0]));
        let neck = frames.ground(apply(&frame, [0.8 * len, 0.0, 0.0]));
        let (nx, nz) = ((tip.0 - tail.0) / len, (tip.1 - tail.1) / len);
        let hw = 0.035;
        let col = color(&a["color"], 1.0);
        ch.draw_series(std::iter::once(PathElement::new(
            vec![tail, neck],
            col.stroke_width(3),
        )))?;
        ch.draw_series(std::iter::once(Polygon::new(
            vec![
                tip,
                (neck.0 - nz * hw, neck.1 + nx * hw),
                (neck.0 + nz * hw, neck.1 - nx * hw),
            ],
            col.filled(),
        )))?;
    }
    Ok(())
}

/// The Plot panel: two plots of message paths, the predictor-corrector's and the
/// reference's relative displacement and sliding.
fn draw_plot_panel(
    right: &DrawingArea<SVGBackend<'_>, Shift>,
    pc: &Trace,
    rf: &Trace,
) -> Result<(), Box<dyn Error>> {
    let plots = right.margin(30, 6, 6, 6);
    let (top, bottom) = plots.split_vertically(282);
    let series = [
        ("rel_disp", "relative displacement x, m"),
        ("slide", "sliding xp, m"),
    ];
    for (area, (key, desc)) in [top, bottom].iter().zip(series) {
        let (a, b) = (pc.column(key).unwrap(), rf.column(key).unwrap());
        let lo = a.iter().chain(b).copied().fold(f64::MAX, f64::min);
        let hi = a.iter().chain(b).copied().fold(f64::MIN, f64::max);
        let pad = 0.08 * (hi - lo).max(1e-9);
        let mut c = ChartBuilder::on(area)
            .margin(8)
            .x_label_area_size(24)
            .y_label_area_size(56)
            .build_cartesian_2d(0f64..1.0, (lo - pad)..(hi + pad))?;
        c.configure_mesh()
            .light_line_style(RGBColor(44, 45, 54))
            .bold_line_style(RGBColor(52, 53, 64))
            .axis_style(DIM)
            .label_style(("sans-serif", 11).into_font().color(&DIM))
            .y_label_formatter(&|v| format!("{v:.4}"))
            .x_desc("log time, s")
            .y_desc(desc)
            .axis_desc_style(("sans-serif", 11).into_font().color(&DIM))
            .draw()?;
        let blue = RGBColor(86, 180, 233);
        let orange = RGBColor(230, 159, 0);
        c.draw_series(LineSeries::new(
            rf.time.iter().zip(b).step_by(50).map(|(t, v)| (*t, *v)),
            orange.stroke_width(2),
        ))?
        .label(format!("/reference/state.{key}"))
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], orange.stroke_width(2)));
        c.draw_series(LineSeries::new(
            pc.time.iter().zip(a).map(|(t, v)| (*t, *v)),
            blue.stroke_width(2),
        ))?
        .label(format!("/predictor-corrector/paper/state.{key}"))
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], blue.stroke_width(2)));
        c.configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(PANEL.mix(0.9))
            .border_style(DIM)
            .label_font(("sans-serif", 12).into_font().color(&FG))
            .draw()?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "docs/img/foxglove-layout.svg".into());
    let tmp = tempfile::tempdir()?;

    // Plot data: the PEPO case, written and read back.
    let case = load_case(Path::new("cases/pepo-mass-accel.toml"))?;
    let result = run_case(case)?;
    let dir = write_case_outputs(&result, tmp.path())?;
    let pepo = read_mcap(&dir.join("pepo-mass-accel.mcap"))?;
    let pc = pepo.state("/predictor-corrector/paper/state").unwrap();
    let rf = pepo.state("/reference/state").unwrap();
    // 3D data: the synthetic rocking trace, written and read back message by message.
    let rock = rocking_messages()?;

    let root = SVGBackend::new(&out, (1200, 640)).into_drawing_area();
    root.fill(&BG)?;
    let (main, footer) = root.split_vertically(608);
    let (left, right) = main.split_horizontally(560);
    let left = left.margin(4, 4, 4, 2);
    let right = right.margin(4, 4, 2, 4);
    left.fill(&PANEL)?;
    right.fill(&PANEL)?;
    panel_header(
        &left,
        "3D   /fe/exact/scene · /fe/exact/forces · /fe/exact/transform",
    );
    panel_header(&right, "Plot");
    draw_3d_panel(&left, &rock)?;
    draw_plot_panel(&right, pc, rf)?;
    footer.draw(&Text::new(
        "Illustration drawn from rockslide MCAP messages (cargo run --example trace_picture), not a Foxglove screenshot. \
         Left: synthetic rocking on the RPEPO geometry, 3 instants. Right: PEPO, mass acceleration (cases/pepo-mass-accel.toml).",
        (10, 8),
        ("sans-serif", 12).into_font().color(&DIM),
    ))?;
    root.present()?;
    println!("wrote {out}");
    Ok(())
}
