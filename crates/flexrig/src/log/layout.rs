//! Foxglove layouts for the MCAP logs (see `docs/foxglove.md`).
//!
//! [`for_log`] is the layout [`write_beside`] puts beside each log (`run.layout.json` beside
//! `run.mcap`): every plot over that log's first contact window (with a margin), so the pulse
//! shapes show without zooming. [`bundled`] is `assets/foxglove/layout.json` (a test keeps the
//! two equal), for any log: the same without the window (a timestamp plot spans the whole log
//! unless given a range). Both show the 3D view without frame labels, with small frame axes, the transforms
//! preloaded, and the force sensor's line over a wide band of the contact force (the two are
//! equal: the sensor samples the contact force).

use std::path::{Path, PathBuf};

use flexrig_rig::RunSummary;
use serde_json::{Value, json};

use crate::Error;

/// A window of log time \[s\] (the plots' time axis: the log starts at 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeWindow {
    /// Start \[s\].
    pub start_s: f64,
    /// End \[s\].
    pub end_s: f64,
}

/// A plot's value axis \[in the plotted unit\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValueRange {
    /// Bottom of the axis.
    pub min: f64,
    /// Top of the axis.
    pub max: f64,
}

/// The value axes of a log's three plots; `None` leaves an axis to the viewer's autoscale.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlotAxes {
    /// Force plot \[N\].
    pub force_n: Option<ValueRange>,
    /// Indentation plot \[mm\].
    pub indentation_mm: Option<ValueRange>,
    /// Accelerations plot \[m/s²\].
    pub accel_mps2: Option<ValueRange>,
}

/// The value axes of a driven log's contact plots; `None` leaves an axis to the viewer's
/// autoscale.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DrivenAxes {
    /// Contact force plot \[N\].
    pub force_n: Option<ValueRange>,
    /// Indentation plot \[mm\] (negative: the gap).
    pub indentation_mm: Option<ValueRange>,
    /// Tip deflection plot \[mm\].
    pub tip_deflection_mm: Option<ValueRange>,
}

/// The contact plots' value axes of a driven run over `window`, from its samples at `time_s`
/// \[s\] of the contact force \[N\], the indentation \[m\] and the tip deflection \[m\]: each over
/// its range in the window (the force from zero) with room above for its one-row legend, so
/// that the floating legend covers no curve.
pub fn driven_axes(
    time_s: &[f64],
    force_n: &[f64],
    indentation_m: &[f64],
    tip_deflection_m: &[f64],
    window: TimeWindow,
) -> DrivenAxes {
    let range = |values: &[f64], scale: f64| {
        let (lo, hi) = time_s
            .iter()
            .zip(values)
            .filter(|(t, v)| **t >= window.start_s && **t <= window.end_s && v.is_finite())
            .fold((0.0_f64, 0.0_f64), |(lo, hi), (_, v)| {
                (lo.min(scale * v), hi.max(scale * v))
            });
        with_legend_room(lo, hi, 1)
    };
    DrivenAxes {
        force_n: range(force_n, 1.0).map(|r| ValueRange { min: 0.0, ..r }),
        indentation_mm: range(indentation_m, 1e3),
        tip_deflection_mm: range(tip_deflection_m, 1e3),
    }
}

/// Fraction of a plot's height the floating legend takes per row of series (with its padding,
/// at the panel heights of the layout's plots): the value axis is raised by that much so the
/// curves stay below the legend.
const LEGEND_ROW: f64 = 0.16;

/// The axis of values from `lo` to `hi` with room above for a legend of `rows` rows, or `None`
/// when there is nothing finite to show.
fn with_legend_room(lo: f64, hi: f64, rows: usize) -> Option<ValueRange> {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return None;
    }
    let covered = (LEGEND_ROW * rows as f64 + 0.04).min(0.6);
    let round = |x: f64| {
        if x > 0.0 {
            nice_ceil(x)
        } else {
            -nice_ceil(-x)
        }
    };
    let min = if lo < 0.0 {
        round(lo - 0.04 * span)
    } else {
        lo
    };
    // the top from the rounded bottom: the band of the legend stays free of values
    Some(ValueRange {
        min,
        max: round(min + (hi - min) / (1.0 - covered)),
    })
}

/// The smallest of 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10^k not below `x` > 0 (the viewer
/// prints the axis ends: round numbers read well).
fn nice_ceil(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|v| *v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade)
}

/// The value axes over `window` of the run `s`, from its sensor samples and its first contact:
/// the force and the indentation from zero to their peaks, the accelerations over their range,
/// each with room for its legend (the plots' floating legends then cover no curve).
pub fn plot_axes(s: &RunSummary, window: TimeWindow) -> PlotAxes {
    let inside = s
        .samples
        .iter()
        .filter(|x| x.t >= window.start_s && x.t <= window.end_s);
    let (mut force, mut a_lo, mut a_hi) = (0.0_f64, f64::INFINITY, f64::NEG_INFINITY);
    for x in inside {
        force = force.max(x.force_n);
        for a in [x.operator_accel_mps2, x.load_accel_mps2] {
            a_lo = a_lo.min(a);
            a_hi = a_hi.max(a);
        }
    }
    let first = s.contacts.first();
    let force = force.max(first.map_or(0.0, |c| c.peak_force_n));
    let indentation_mm = first.map_or(0.0, |c| c.max_indentation_m * 1e3);
    PlotAxes {
        force_n: with_legend_room(0.0, force, 2),
        indentation_mm: with_legend_room(0.0, indentation_mm, 1),
        accel_mps2: with_legend_room(a_lo.min(0.0), a_hi.max(0.0), 2),
    }
}

/// Fraction of the contact's duration shown before its onset and after its end.
const MARGIN: f64 = 0.15;

/// The first contact of a run with a margin of [`MARGIN`] of its duration on each side (a run
/// stopped at the peak: onset to the end of the run), or `None` without a contact.
pub fn contact_window(s: &RunSummary) -> Option<TimeWindow> {
    let c = s.contacts.first()?;
    let end = c
        .duration_s
        .map_or(s.duration_s, |d| c.onset_time_s + d)
        .max(c.time_of_peak_s);
    let margin = MARGIN * (end - c.onset_time_s).max(0.0);
    let window = TimeWindow {
        start_s: (c.onset_time_s - margin).max(0.0),
        end_s: end + margin,
    };
    (window.end_s > window.start_s && window.end_s.is_finite()).then_some(window)
}

/// `run.layout.json` beside `run.mcap` \[path\].
pub fn path_beside(log: &Path) -> PathBuf {
    let stem = log
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    log.with_file_name(format!("{stem}.layout.json"))
}

/// Writes the layout of the run `summary` beside `log` (see [`path_beside`]), atomically: the
/// plots over its first contact ([`contact_window`], [`plot_axes`]), or over the whole log for a
/// run without a contact or that failed (`None`).
pub fn write_beside(log: &Path, summary: Option<&RunSummary>) -> Result<(), Error> {
    let layout = match summary.and_then(|s| contact_window(s).map(|w| (s, w))) {
        Some((s, w)) => for_run(w, plot_axes(s, w)),
        None => for_log(None),
    };
    let layout = match summary {
        Some(s) if s.drive.is_some() => with_drive(layout),
        _ => layout,
    };
    let text =
        serde_json::to_string_pretty(&layout).expect("a layout built from json! values serialises");
    crate::shared::output::write_atomic(&path_beside(log), format!("{text}\n").as_bytes())
}

/// The bundled layout (`assets/foxglove/layout.json`), for any log: the plots over the whole
/// log (a log without a contact gets this one beside it).
pub fn bundled() -> Value {
    for_log(None)
}

/// The layout of one log whose first contact spans `window` (`None`: the whole log), the value
/// axes autoscaled. The plots are synced: zooming one zooms all.
pub fn for_log(window: Option<TimeWindow>) -> Value {
    with_axes(window, PlotAxes::default())
}

/// The layout of one run's log: the plots over its first contact's `window`, on `axes`.
pub fn for_run(window: TimeWindow, axes: PlotAxes) -> Value {
    with_axes(Some(window), axes)
}

fn with_axes(window: Option<TimeWindow>, axes: PlotAxes) -> Value {
    layout([
        plot(
            "Force",
            // the first series is drawn on top: the sensor's line over the contact's band
            vec![
                series(
                    "/sensors/force.force_n",
                    "force sensor, 50 kHz [N]",
                    SENSOR,
                    1.0,
                ),
                series(
                    "/contact.force_n",
                    "contact force, every step [N]",
                    BAND,
                    12.0,
                ),
            ],
            window,
            axes.force_n,
        ),
        plot(
            "Indentation",
            vec![series(
                "/contact.indentation_mm",
                "indentation [mm]",
                CONTACT,
                2.0,
            )],
            window,
            axes.indentation_mm,
        ),
        plot(
            "Accelerations (along the strike)",
            vec![
                series(
                    "/sensors/accel/operator.accel_mps2",
                    "operator block [m/s²]",
                    OPERATOR,
                    1.0,
                ),
                series("/sensors/accel/load.accel_mps2", "load [m/s²]", LOAD, 1.0),
            ],
            window,
            axes.accel_mps2,
        ),
    ])
}

/// A test-bed layout ([`for_run`], [`for_log`]) for a run with a motor on the robot joint
/// (`robot.drive`): below the 3D view, over the whole run (not synced with the contact's
/// plots), the robot joint's speed (commanded, the motor side and the link after the torsion
/// spring), the motor's torque (at the joint and at the motor) with the link's moment on the
/// hub (the CJ's spring, the CL's beam root), and the link's deflection from the hub's line.
pub fn with_drive(mut layout: Value) -> Value {
    let speed = whole_run_plot(
        "Robot joint speed",
        vec![
            series(
                "/drive/command.speed_rad_s",
                "commanded [rad/s]",
                SENSOR,
                1.0,
            ),
            series(
                "/drive/joint.speed_rad_s",
                "motor side [rad/s]",
                CONTACT,
                2.0,
            ),
            series(
                "/drive/link.speed_rad_s",
                "link, after the spring [rad/s]",
                LOAD,
                1.0,
            ),
        ],
    );
    let torque = whole_run_plot(
        "Motor torque",
        vec![
            series(
                "/drive/torque.joint_nm",
                "at the joint [N·m]",
                OPERATOR,
                2.0,
            ),
            series("/drive/torque.motor_nm", "at the motor [N·m]", LOAD, 1.0),
            series(
                "/drive/load.moment_nm",
                "link on the hub [N·m]",
                SENSOR,
                1.0,
            ),
        ],
    );
    let deflection = whole_run_plot(
        "Link deflection",
        vec![series(
            "/drive/load.deflection_mm",
            "tip from the hub's line [mm]",
            CONTACT,
            1.0,
        )],
    );
    // the legends above the plots: a floating one would cover the torque's peak
    for (id, mut p) in [
        ("Plot!drive_speed", speed),
        ("Plot!drive_torque", torque),
        ("Plot!drive_deflection", deflection),
    ] {
        p["legendDisplay"] = json!("top");
        layout["configById"][id] = p;
    }
    let view = layout["layout"]["first"].take();
    layout["layout"]["first"] = json!({
        "first": view,
        "second": {
            "first": "Plot!drive_speed",
            "second": {
                "first": "Plot!drive_torque",
                "second": "Plot!drive_deflection",
                "direction": "row"
            },
            "direction": "row",
            "splitPercentage": 33.3
        },
        "direction": "column",
        "splitPercentage": 45
    });
    layout
}

/// A plot over the whole run, not synced with the contact's plots.
fn whole_run_plot(title: &str, paths: Vec<Value>) -> Value {
    let mut p = plot(title, paths, None, None);
    p["isSynced"] = json!(false);
    p
}

/// The window from `start_s` to `end_s` \[s\] with a margin of [`MARGIN`] of its length on each
/// side (not before 0).
pub fn window_around(start_s: f64, end_s: f64) -> TimeWindow {
    let margin = MARGIN * (end_s - start_s).max(0.0);
    TimeWindow {
        start_s: (start_s - margin).max(0.0),
        end_s: end_s + margin,
    }
}

/// Writes [`driven_for_log`]`(window, commanded, axes)` beside the driven run's `log`, atomically.
pub fn write_driven_beside(
    log: &Path,
    window: Option<TimeWindow>,
    commanded: bool,
    axes: DrivenAxes,
) -> Result<(), Error> {
    let text = serde_json::to_string_pretty(&driven_for_log(window, commanded, axes))
        .expect("a layout built from json! values serialises");
    crate::shared::output::write_atomic(&path_beside(log), format!("{text}\n").as_bytes())
}

/// The layout of a driven run's log (plots only: the driven strike has no 3D view). On the
/// left, over the whole run: the joint's angle and speed (commanded and actual; the commanded
/// series only when `commanded`) and the motor's torque at the joint with the link's moment; on
/// the right, over the contact `window` (synced): the contact force, the indentation and the
/// tip deflection, on the value `axes` (see [`driven_axes`]).
pub fn driven_for_log(window: Option<TimeWindow>, commanded: bool, axes: DrivenAxes) -> Value {
    let pair = |topic: &str, field: &str, what: &str, unit: &str| {
        let mut paths = Vec::new();
        if commanded {
            paths.push(series(
                &format!("/drive/command.{field}"),
                &format!("commanded {what} [{unit}]"),
                SENSOR,
                1.0,
            ));
        }
        paths.push(series(
            &format!("{topic}.{field}"),
            &format!("actual {what} [{unit}]"),
            CONTACT,
            2.0,
        ));
        paths
    };
    let whole = whole_run_plot;
    let angle = whole(
        "Joint angle",
        pair("/drive/joint", "angle_rad", "joint angle", "rad"),
    );
    let speed = whole(
        "Joint speed",
        pair("/drive/joint", "speed_rad_s", "joint speed", "rad/s"),
    );
    let torque = whole(
        "Motor torque and link moment (at the joint)",
        vec![
            series(
                "/drive/torque.joint_nm",
                "motor torque at the joint [N·m]",
                OPERATOR,
                2.0,
            ),
            series(
                "/link.moment_nm",
                "spring or beam-root moment [N·m]",
                LOAD,
                1.0,
            ),
        ],
    );
    let force = plot(
        "Contact force",
        vec![series("/contact.force_n", "contact force [N]", SENSOR, 2.0)],
        window,
        axes.force_n,
    );
    let indentation = plot(
        "Indentation",
        vec![series(
            "/contact.indentation_mm",
            "indentation [mm] (negative: the gap)",
            CONTACT,
            2.0,
        )],
        window,
        axes.indentation_mm,
    );
    let deflection = plot(
        "Tip deflection",
        vec![series(
            "/link.tip_deflection_mm",
            "tip deflection from the hub's line [mm]",
            LOAD,
            2.0,
        )],
        window,
        axes.tip_deflection_mm,
    );
    json!({
        "configById": {
            "Plot!angle": angle,
            "Plot!speed": speed,
            "Plot!torque": torque,
            "Plot!force": force,
            "Plot!indentation": indentation,
            "Plot!deflection": deflection,
        },
        "globalVariables": {},
        "userNodes": {},
        "playbackConfig": { "speed": 0.05 },
        "layout": {
            "first": {
                "first": "Plot!angle",
                "second": { "first": "Plot!speed", "second": "Plot!torque", "direction": "column" },
                "direction": "column",
                "splitPercentage": 33
            },
            "second": {
                "first": "Plot!force",
                "second": { "first": "Plot!indentation", "second": "Plot!deflection", "direction": "column" },
                "direction": "column",
                "splitPercentage": 33
            },
            "direction": "row",
            "splitPercentage": 50
        }
    })
}

/// Series colours: the contact force as a wide pale band under the force sensor's dark line.
const BAND: &str = "#ffc48a";
const SENSOR: &str = "#1d3557";
const CONTACT: &str = "#e76f51";
const OPERATOR: &str = "#4cc9f0";
const LOAD: &str = "#ff6b6b";

/// One plotted series, a line `width` pixels wide.
fn series(path: &str, label: &str, color: &str, width: f64) -> Value {
    json!({
        "value": path,
        "enabled": true,
        "timestampMethod": "receiveTime",
        "label": label,
        "color": color,
        "lineSize": width,
        "showLine": true,
    })
}

/// A plot panel's configuration: log time on the x axis over `window`, the values on `values`
/// (`None`: autoscaled).
fn plot(
    title: &str,
    paths: Vec<Value>,
    window: Option<TimeWindow>,
    values: Option<ValueRange>,
) -> Value {
    let mut config = json!({
        "paths": paths,
        "showXAxisLabels": true,
        "showYAxisLabels": true,
        "showLegend": true,
        "legendDisplay": "floating",
        "showPlotValuesInLegend": false,
        "isSynced": true,
        "xAxisVal": "timestamp",
        "sidebarDimension": 240,
        "foxglovePanelTitle": title,
        "lichtblickPanelTitle": title,
    });
    if let (Some(w), Some(c)) = (window, config.as_object_mut()) {
        c.insert("minXValue".into(), json!(w.start_s));
        c.insert("maxXValue".into(), json!(w.end_s));
    }
    if let (Some(v), Some(c)) = (values, config.as_object_mut()) {
        c.insert("minYValue".into(), json!(v.min));
        c.insert("maxYValue".into(), json!(v.max));
    }
    config
}

/// The 3D panel: the rig seen from above the operator's side, frame labels off, small axes,
/// transforms preloaded.
fn three_d() -> Value {
    json!({
        "cameraState": {
            "distance": 0.75,
            "perspective": true,
            "phi": 30,
            "thetaOffset": -90,
            "targetOffset": [0.17, -0.02, 0.0],
            "target": [0, 0, 0],
            "targetOrientation": [0, 0, 0, 1],
            "fovy": 45,
            "near": 0.01,
            "far": 100
        },
        "followMode": "follow-none",
        "scene": {
            "enableStats": false,
            "transforms": {
                "showLabel": false,
                "axisScale": 0.15,
                "lineWidth": 0,
                "enablePreloading": true
            }
        },
        "transforms": {},
        "topics": { "/scene": { "visible": true } },
        "layers": {
            "grid": {
                "visible": true,
                "frameLocked": true,
                "label": "Grid (5 cm)",
                "instanceId": "grid",
                "layerId": "foxglove.Grid",
                "size": 1,
                "divisions": 20,
                "lineWidth": 1,
                "color": "#248eff33",
                "position": [0, 0, 0],
                "rotation": [0, 0, 0]
            }
        },
        "publish": { "type": "point" },
        "imageMode": {},
        "foxglovePanelTitle": "Rig",
        "lichtblickPanelTitle": "Rig"
    })
}

/// The 3D view on the left, the three plots stacked on the right.
fn layout([force, indentation, third]: [Value; 3]) -> Value {
    json!({
        "configById": {
            "3D!rig": three_d(),
            "Plot!force": force,
            "Plot!indentation": indentation,
            "Plot!accel": third,
        },
        "globalVariables": {},
        "userNodes": {},
        "playbackConfig": { "speed": 0.05 },
        "layout": {
            "first": "3D!rig",
            "second": {
                "first": "Plot!force",
                "second": { "first": "Plot!indentation", "second": "Plot!accel", "direction": "column" },
                "direction": "column",
                "splitPercentage": 34
            },
            "direction": "row",
            "splitPercentage": 50
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every panel the layout tree names, in order (the leaves of the split tree).
    fn leaves(node: &Value, out: &mut Vec<String>) {
        match node {
            Value::String(id) => out.push(id.clone()),
            Value::Object(o) => {
                leaves(&o["first"], out);
                leaves(&o["second"], out);
            }
            _ => panic!("not a layout node: {node}"),
        }
    }

    #[test]
    fn a_run_with_a_motor_gets_the_drive_plots_below_the_3d_view() {
        let plain = for_log(None);
        let driven = with_drive(for_log(None));
        let (mut a, mut b) = (Vec::new(), Vec::new());
        leaves(&plain["layout"], &mut a);
        leaves(&driven["layout"], &mut b);
        assert_eq!(
            b,
            [
                "3D!rig",
                "Plot!drive_speed",
                "Plot!drive_torque",
                "Plot!drive_deflection",
                "Plot!force",
                "Plot!indentation",
                "Plot!accel"
            ]
        );
        // every panel named is configured, and nothing of the plain layout is lost
        for id in &b {
            assert!(driven["configById"].get(id).is_some(), "{id}");
        }
        assert!(a.iter().all(|id| b.contains(id)));
        let text = driven.to_string();
        for topic in [
            "/drive/command.speed_rad_s",
            "/drive/joint.speed_rad_s",
            "/drive/link.speed_rad_s",
            "/drive/torque.joint_nm",
            "/drive/torque.motor_nm",
            "/drive/load.moment_nm",
            "/drive/load.deflection_mm",
        ] {
            assert!(text.contains(topic), "{topic}");
        }
        assert_eq!(
            driven["configById"]["Plot!drive_speed"]["isSynced"],
            json!(false)
        );
    }

    #[test]
    fn driven_contact_plots_keep_their_curves_below_the_legend() {
        // a half-sine pulse of 2 ms from 1 ms, the gap closing before it, the tip bent back
        let t: Vec<f64> = (0..=400).map(|i| 1e-5 * f64::from(i)).collect();
        let pulse = |t: f64| {
            if (1e-3..=3e-3).contains(&t) {
                (std::f64::consts::PI * (t - 1e-3) / 2e-3).sin()
            } else {
                0.0
            }
        };
        let force: Vec<f64> = t.iter().map(|&t| 3500.0 * pulse(t)).collect();
        let indentation: Vec<f64> = t
            .iter()
            .map(|&t| {
                if t < 1e-3 {
                    2.0 * (t - 1e-3)
                } else {
                    6e-3 * pulse(t)
                }
            })
            .collect();
        let deflection: Vec<f64> = t.iter().map(|&t| -2.9e-6 * pulse(t)).collect();
        let window = window_around(1e-3, 3e-3);
        let axes = driven_axes(&t, &force, &indentation, &deflection, window);
        let covered = LEGEND_ROW + 0.04;
        // (lowest value, highest value) in the window, as plotted
        for (axis, lo, hi) in [
            (axes.force_n, 0.0, 3500.0),
            (axes.indentation_mm, 2e3 * (window.start_s - 1e-3), 6.0),
            (axes.tip_deflection_mm, -2.9e-3, 0.0),
        ] {
            let r = axis.unwrap();
            assert!(r.min <= lo + 1e-12 && r.max > hi, "{r:?} for [{lo}, {hi}]");
            // the legend's band at the top holds no value
            let top_free = (r.max - hi) / (r.max - r.min);
            assert!(top_free >= covered - 1e-12, "{r:?}: {top_free}");
        }
        assert_eq!(axes.force_n.unwrap().min, 0.0);
        let layout = driven_for_log(Some(window), true, axes);
        let force = &layout["configById"]["Plot!force"];
        assert_eq!(force["maxYValue"], json!(axes.force_n.unwrap().max));
        let deflection = &layout["configById"]["Plot!deflection"];
        assert_eq!(
            deflection["minYValue"],
            json!(axes.tip_deflection_mm.unwrap().min)
        );
    }

    #[test]
    fn the_bundled_layout_file_is_the_generated_one() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/foxglove/layout.json"
        );
        let expected = bundled();
        if std::env::var_os("FLEXRIG_WRITE_LAYOUT").is_some() {
            let text = serde_json::to_string_pretty(&expected).unwrap();
            std::fs::write(path, format!("{text}\n")).unwrap();
        }
        let file: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        assert_eq!(
            file, expected,
            "assets/foxglove/layout.json differs from foxglove_layout::bundled(); regenerate \
             it with FLEXRIG_WRITE_LAYOUT=1 cargo test --release -p flexrig bundled_layout"
        );
    }

    #[test]
    fn axis_ends_are_round_and_hold_the_values_below_the_legend() {
        assert_eq!(nice_ceil(415.4), 500.0);
        assert_eq!(nice_ceil(2.1), 2.5);
        assert_eq!(nice_ceil(1028.6), 1200.0);
        assert_eq!(nice_ceil(93.7), 100.0);
        assert_eq!(nice_ceil(3.0), 3.0);
        let r = with_legend_room(-60.0, 640.0, 2).unwrap();
        assert_eq!((r.min, r.max), (-100.0, 1200.0));
        // the curve's top stays below the two legend rows (36 % of the height)
        assert!(640.0 <= r.min + (1.0 - 0.36) * (r.max - r.min));
        let r = with_legend_room(0.0, 266.0, 2).unwrap();
        assert_eq!((r.min, r.max), (0.0, 500.0));
        assert!(with_legend_room(0.0, 0.0, 1).is_none());
        assert!(with_legend_room(0.0, f64::NAN, 1).is_none());
    }

    #[test]
    fn layout_path_sits_beside_the_log() {
        assert_eq!(
            path_beside(Path::new("out/cl_iron_0.mcap")),
            Path::new("out/cl_iron_0.layout.json")
        );
        assert_eq!(path_beside(Path::new("run")), Path::new("run.layout.json"));
    }

    #[test]
    fn every_plot_of_a_log_layout_spans_the_window() {
        let w = TimeWindow {
            start_s: 0.28,
            end_s: 0.287,
        };
        let layout = for_log(Some(w));
        let configs = layout["configById"].as_object().unwrap();
        let plots: Vec<_> = configs
            .iter()
            .filter(|(k, _)| k.starts_with("Plot!"))
            .collect();
        assert_eq!(plots.len(), 3);
        for (id, c) in plots {
            assert_eq!(c["xAxisVal"], "timestamp", "{id}");
            assert_eq!(c["minXValue"], 0.28, "{id}");
            assert_eq!(c["maxXValue"], 0.287, "{id}");
        }
        let t = &configs["3D!rig"]["scene"]["transforms"];
        assert_eq!(t["showLabel"], false);
        assert_eq!(t["enablePreloading"], true);
        assert!(t["axisScale"].as_f64().unwrap() < 1.0);
        // without a contact the plots span the whole log
        let whole = for_log(None);
        assert!(whole["configById"]["Plot!force"].get("minXValue").is_none());
    }
}
