//! Every figure at one column (3.5 in) and two columns (7 in): its text read back is at least
//! [`MIN_TEXT_PT`] at that width, it states that width, it contains no code notation, and (fig9)
//! its labels are the inputs that ran. Set `FLEXRIG_FIGURE_DIR` to keep the SVGs and PNGs.

use flexrig_impact::eta::{EffectiveGamma, EtaRow};
use flexrig_impact::map::{LogRange, MapPoint, MapSpec};
use flexrig_impact::rotor::RotorPoint;
use flexrig_lumped::fig6::{Fig6Case, cases, fig6};

use crate::fe::eta_map::ComputedMap;
use crate::fe::payload::PayloadRow;
use crate::fe::payload::figure::*;
use crate::plots::inspect::{min_text_pt, printed_width, texts, texts_outside};
use crate::plots::*;
use crate::testbed::experiment::fig9::*;
use crate::testbed::experiment::{GroupStats, RatioStats, RunInputs};

const WIDTHS: [f64; 2] = [252.0, 504.0];

/// Checks `svg` drawn at `width_pt`: its printed width, its smallest text, no code notation;
/// returns its text.
fn check(name: &str, svg: &str, width_pt: f64) -> String {
    let (inches, _) = printed_width(svg).unwrap_or_else(|| panic!("{name}: no printed width"));
    assert!(
        (inches - width_pt / 72.0).abs() < 1e-9,
        "{name}: {inches} in"
    );
    let min = min_text_pt(svg).unwrap_or_else(|| panic!("{name}: no text"));
    assert!(
        min >= MIN_TEXT_PT - 1e-3,
        "{name} at {width_pt} pt: text of {min:.2} pt"
    );
    let outside = texts_outside(svg);
    assert!(
        outside.is_empty(),
        "{name} at {width_pt} pt: text beyond the edge {outside:?}"
    );
    let text = texts(svg).join("\n");
    for code in ["1e8", "1e-", "e-5", "v0 ", "f_CL/f_CJ", "issue", "NaN"] {
        assert!(!text.contains(code), "{name}: '{code}' in\n{text}");
    }
    if let Some(dir) = std::env::var_os("FLEXRIG_FIGURE_DIR") {
        let dir = std::path::PathBuf::from(dir);
        let _ = std::fs::create_dir_all(&dir);
        let stem = format!("{name}_{}", width_pt as u32);
        std::fs::write(dir.join(format!("{stem}.svg")), svg).unwrap();
        std::fs::write(
            dir.join(format!("{stem}.png")),
            svg_to_png(svg, 150.0).unwrap(),
        )
        .unwrap();
    }
    text
}

fn inputs(design: &str, material: &str, m_h: f64, m_e: f64) -> RunInputs {
    RunInputs {
        design: design.into(),
        block_material: material.into(),
        block_mass_kg: m_h,
        payload_kg: m_e,
    }
}

fn group(scene: &str, inputs: RunInputs, mean: f64, n: usize) -> GroupStats {
    GroupStats {
        scene: scene.into(),
        inputs,
        n,
        mean_peak_force_n: mean,
        ci95_n: (n > 1).then_some(0.02 * mean),
    }
}

/// fig9 with the experiment's scenes as `design`, operator masses and payloads given.
fn fig9(design_cj: &str, design_cl: &str, m_h: f64, m_e: f64, light: f64) -> Vec<GroupStats> {
    let mut g = Vec::new();
    for (case, material, mass) in [
        ("aluminium", "skinned_aluminium", m_h),
        ("iron", "skinned_iron", 4.008),
    ] {
        g.push(group(
            &format!("cj_{case}"),
            inputs(design_cj, material, mass, m_e),
            100.0 + mass,
            5,
        ));
        g.push(group(
            &format!("cl_{case}"),
            inputs(design_cl, material, mass, m_e),
            99.0 + mass,
            5,
        ));
    }
    g.push(group(
        "cj_light_load",
        inputs(design_cj, "skinned_aluminium", m_h, light),
        60.0,
        1,
    ));
    g.push(group(
        "cl_light_load",
        inputs(design_cl, "skinned_aluminium", m_h, light),
        56.0,
        1,
    ));
    g
}

fn ratios() -> Vec<RatioStats> {
    vec![
        RatioStats {
            case: "aluminium".into(),
            pairs: 5,
            mean_cl_over_cj: 0.990008,
            ci95: Some(3.3e-7),
        },
        RatioStats {
            case: "iron".into(),
            pairs: 5,
            mean_cl_over_cj: 0.985,
            ci95: Some(0.004),
        },
        RatioStats {
            case: "light_load".into(),
            pairs: 1,
            mean_cl_over_cj: 0.935,
            ci95: None,
        },
    ]
}

const JITTER: Jitter = Jitter {
    sd_deg: 0.5,
    seed: 7,
};

#[test]
fn fig9_labels_are_the_inputs_that_ran() {
    for w in WIDTHS {
        // the paper's inputs
        let text = check(
            "fig9",
            &fig9_svg(&fig9("cj", "cl", 0.398, 0.412, 0.1), &ratios(), JITTER, w).unwrap(),
            w,
        );
        for label in [
            "(a) m_e = 412 g",
            "(b) m_e = 100 g",
            "m_h = 398 g",
            "m_h = 4008 g",
            "aluminium",
            "iron",
            "(c) CL/CJ",
            "0.990\nCI < 0.001",
            "0.985\n± 0.004",
            "0.935\n1 pair, no CI",
            "release-angle scatter (σ = 0.5°, seed 7)",
            // panel (b) is one run: the note says so rather than "mean of 5 runs" for both
            "Bars: (a) mean of 5 runs ± 95 % CI; (b) one run, no confidence interval.",
        ] {
            let joined = text.replace('\n', " ");
            assert!(
                text.contains(label) || joined.contains(label),
                "{label} missing at {w} pt:\n{text}"
            );
        }
        // robot.payload_kg = 1, operator.block_mass_kg = 4: every label follows
        let text = check(
            "fig9_set",
            &fig9_svg(&fig9("cj", "cl", 4.0, 1.0, 1.0), &ratios(), JITTER, w).unwrap(),
            w,
        );
        assert!(text.contains("(a) m_e = 1000 g") && text.contains("(b) m_e = 1000 g"));
        assert!(text.contains("m_h = 4000 g"), "{text}");
        // at two columns the ratio panel's three "m_e = 1000 g" would run together: they are
        // written in kilograms there
        if w > 400.0 {
            let kg = text.lines().filter(|l| *l == "m_e = 1 kg").count();
            assert_eq!(kg, 3, "{text}");
        }
        for stale in ["412 g", "0.1 kg", "100 g", "398 g"] {
            assert!(!text.contains(stale), "{stale} at {w} pt:\n{text}");
        }
        // robot.design = cl everywhere: no CJ is claimed
        let text = check(
            "fig9_cl",
            &fig9_svg(&fig9("cl", "cl", 0.398, 0.412, 0.1), &ratios(), JITTER, w).unwrap(),
            w,
        );
        assert!(text.contains("(c) CL/CL"), "{text}");
        assert!(!text.contains("CJ"), "{text}");
    }
}

#[test]
fn fig6_and_its_fe_points_at_print_size() {
    let curves = fig6(41).unwrap();
    let points: Vec<Fig6Point> = curves
        .iter()
        .map(|c| Fig6Point {
            case: c.case,
            n: c.n,
            eta_fe: c.eta_at_2_3 * 1.01,
            gamma: if c.case.m_e > 1.0 { None } else { Some(0.7) },
        })
        .collect();
    for w in WIDTHS {
        let text = check(
            "fig6",
            &fig6_svg(&curves, &flexrig_lumped::fig6::Fig6Design::PAPER, w).unwrap(),
            w,
        );
        assert!(text.contains("η(2/3)"));
        let text = check(
            "eta_fig6",
            &fig6_with_points_svg(
                &curves,
                &points,
                &flexrig_lumped::fig6::Fig6Design::PAPER,
                w,
            )
            .unwrap(),
            w,
        );
        assert!(text.contains("η_FE, m_e = 10 kg"), "{text}");
    }
}

fn eta_row(case: Fig6Case, n: f64, eta: f64, gamma: EffectiveGamma) -> EtaRow {
    EtaRow {
        case,
        n,
        f_cj_n: 100.0,
        f_cl_n: 100.0 * eta,
        eta_fe: eta,
        eta_lumped_2_3: eta * 1.02,
        f_cj_lumped_n: 101.0,
        gamma_eff: gamma,
        f_placed_n: 100.0 * eta * 1.01,
        window: None,
        severity: None,
    }
}

#[test]
fn eta_dot_plot_at_print_size() {
    let rows: Vec<EtaRow> = cases()
        .iter()
        .flat_map(|c| [1.0, 2.0].map(|n| eta_row(*c, n, 0.3 + 0.08 * n, EffectiveGamma::Fits(0.7))))
        .collect();
    for w in WIDTHS {
        let text = check("eta", &eta_svg(&rows, "held", w).unwrap(), w);
        assert!(text.contains("10⁸ N/m"), "{text}");
    }
}

/// A map of `n`×`n` points, γ_eff fitting at none (`fits` false) or every point.
fn map(n: usize, fits: bool) -> ComputedMap {
    let range = LogRange {
        from: 0.01,
        to: 10.0,
        points: n,
    };
    let spec = MapSpec {
        m_h: 4.0,
        n: 2.0,
        mass_ratio: range,
        stiffness_ratio: range,
    };
    let mut points = Vec::new();
    for (iy, y) in range.values().into_iter().enumerate() {
        for (ix, x) in range.values().into_iter().enumerate() {
            let eta = 0.5 + 0.05 * (ix + iy) as f64;
            let gamma = if fits {
                EffectiveGamma::Fits(0.6)
            } else {
                EffectiveGamma::AboveGammaOne
            };
            let case = Fig6Case {
                m_h: 4.0,
                k_delta: y * 1e8,
                m_e: x * 10.0,
            };
            points.push(MapPoint {
                mass_ratio: x,
                stiffness_ratio: y,
                row: Ok(eta_row(case, 2.0, eta, gamma)),
            });
        }
    }
    ComputedMap {
        spec,
        points,
        seconds: 0.0,
    }
}

#[test]
fn eta_map_shows_gamma_eff_only_with_values() {
    for w in WIDTHS {
        let none = crate::fe::eta_map::svg(
            &map(4, false),
            "held joint",
            &flexrig_lumped::fig6::Fig6Design::PAPER,
            w,
        )
        .unwrap();
        let text = check("eta_map", &none, w);
        assert!(!text.contains("effective γ ("), "{text}");
        // (broken into lines at one column)
        assert!(
            text.replace('\n', " ")
                .contains("no γ in (0, 1] fits at any point (16 need γ > 1"),
            "{text}"
        );
        let some = crate::fe::eta_map::svg(
            &map(4, true),
            "held joint",
            &flexrig_lumped::fig6::Fig6Design::PAPER,
            w,
        )
        .unwrap();
        let text = check("eta_map_gamma", &some, w);
        assert!(text.contains("effective γ"), "{text}");
    }
}

#[test]
fn eta_rotor_at_print_size() {
    let mut points = Vec::new();
    for c in cases() {
        for n in [1.0, 2.0] {
            for e in -4..=4 {
                points.push(RotorPoint {
                    case: c,
                    n,
                    inertia_ratio: Some(10f64.powi(e)),
                    f_cj_n: 100.0,
                    f_cl_n: 90.0,
                    eta_fe: 0.8 + 0.01 * f64::from(e) + 0.01 * n,
                    severity: None,
                });
            }
            points.push(RotorPoint {
                case: c,
                n,
                inertia_ratio: None,
                f_cj_n: 100.0,
                f_cl_n: 90.0,
                eta_fe: 0.9,
                severity: None,
            });
        }
    }
    for w in WIDTHS {
        let text = check(
            "eta_rotor",
            &eta_rotor_svg(
                &points,
                "elastic Hertz contact; m_r = 10 kg, k_c = 10⁸ N/mⁿ, v_0 = 2 m/s",
                w,
            )
            .unwrap(),
            w,
        );
        for n in [2, 1] {
            let label = format!("held joint, n = {n}");
            assert_eq!(text.lines().filter(|l| *l == label).count(), 1, "{text}");
        }
    }
}

#[test]
fn payload_and_prb_and_bench_at_print_size() {
    let rows: Vec<PayloadRow> = (0..9)
        .map(|i| {
            let m = 0.01 * 10f64.powf(f64::from(i) / 4.0);
            PayloadRow {
                payload_kg: m,
                cj_peak_n: 100.0 + 50.0 * m,
                cl_peak_n: 90.0 + 52.0 * m,
                ratio: (90.0 + 52.0 * m) / (100.0 + 50.0 * m),
            }
        })
        .collect();
    let path = flexrig_beam::prb::trace_tip_path_with(
        flexrig_beam::Kinematics::Corotational,
        8,
        &flexrig_beam::prb::default_load_indices(),
    )
    .unwrap();
    let fit =
        flexrig_beam::prb::fit_prb(&path, flexrig_beam::prb::ErrorMeasure::Deflection).unwrap();
    let panels = vec![Panel {
        title: "(a) transients: elements × time step".into(),
        note: Some("a note on the reference, long enough to wrap at one column width".into()),
        series: (0..6)
            .map(|i| Series {
                label: format!("tip step load P = EI/L², 1000 steps of 1 ms, ρ∞ 0.9, case {i}"),
                points: vec![(1e-4 * f64::from(i + 1), 1e-3), (1e-3, 1e-5)],
            })
            .collect(),
    }];
    for w in WIDTHS {
        let text = check(
            "payload",
            &payload_svg(&rows, "skinned aluminium operator, m_h = 398 g", w).unwrap(),
            w,
        );
        // each paper payload's label is two short lines (name, then mass) right of its line
        let lines: Vec<&str> = text.lines().collect();
        for (name, mass) in [("light load", "100 g"), ("test bed", "412 g")] {
            assert_eq!(lines.iter().filter(|l| **l == name).count(), 2, "{text}");
            assert_eq!(lines.iter().filter(|l| **l == mass).count(), 2, "{text}");
        }
        let text = check("prb", &prb_svg(&path, &fit, "corotational", w).unwrap(), w);
        assert!(text.contains("Θ_max"), "{text}");
        check(
            "bench",
            &work_precision_svg("Work–precision, beam", "relative error", &panels, false, w)
                .unwrap(),
            w,
        );
    }
}
