use super::*;
use flexrig_lumped::fig6::fig6;

/// The γ at which `curve` takes the value `eta` (linear between samples), if it does.
fn gamma_at(curve: &EtaCurve, eta: f64) -> Option<f64> {
    curve
        .gamma
        .windows(2)
        .zip(curve.eta.windows(2))
        .find(|(_, e)| (e[0] - eta) * (e[1] - eta) <= 0.0 && e[0] != e[1])
        .map(|(g, e)| g[0] + (eta - e[0]) / (e[1] - e[0]) * (g[1] - g[0]))
}

/// The held-joint η_FE of docs/impact-fe.md, in the order of the curves.
const ETA_FE: [f64; 16] = [
    0.9207, 1.0001, 0.9913, 1.0000, 0.2795, 0.3208, 0.9650, 0.9580, 0.9943, 1.0000, 0.9952, 0.9999,
    0.2095, 0.2277, 0.8734, 0.8508,
];

fn points(curves: &[EtaCurve]) -> Vec<Fig6Point> {
    curves
        .iter()
        .map(|c| {
            let i = 2 * cases_index(c) + usize::from(c.n == 2.0);
            let eta_fe = ETA_FE[i];
            Fig6Point {
                case: c.case,
                n: c.n,
                eta_fe,
                gamma: gamma_at(c, eta_fe),
            }
        })
        .collect()
}

fn cases_index(c: &EtaCurve) -> usize {
    flexrig_lumped::fig6::cases()
        .iter()
        .position(|k| *k == c.case)
        .unwrap()
}

#[test]
fn fig6_with_sixteen_points_renders() {
    let curves = fig6(101).unwrap();
    let pts = points(&curves);
    assert_eq!(pts.len(), 16);
    let off = pts.iter().filter(|p| p.gamma.is_none()).count();
    assert!((4..16).contains(&off), "{off} points off the curves");
    let svg = fig6_with_points_svg(&curves, &pts, &Fig6Design::PAPER, 504.0).unwrap();
    assert!(svg.starts_with("<svg width=\"7in\""), "{}", &svg[..80]);
    assert!(svg.contains("η<tspan"));
    assert!(svg.contains("off its curve"));
    // 16 markers plus 6 in the legend, each a polygon
    assert_eq!(svg.matches("<polygon").count(), 22);
    // the curves alone keep the original figure
    let plain = fig6_svg(&curves, &Fig6Design::PAPER, 504.0).unwrap();
    assert!(!plain.contains("off its curve"));
    assert!(round_up_1(9.3e-5) > 9.99e-5 && round_up_1(8.2e-5) < 9.01e-5);
}

/// Panel (c) of the paper's points (m_h = 1000 kg, k_δ = 10⁸ N/m) has three η_FE within
/// 0.006 of 1 at γ ≈ 1: they are set in a column below their points, covering neither each
/// other nor the fourth marker, their points kept exactly, one leader line, their values in
/// the figure's text.
#[test]
fn markers_that_would_cover_each_other_are_set_apart() {
    let curves = fig6(101).unwrap();
    let pts = points(&curves);
    let panel: Vec<&Fig6Point> = pts
        .iter()
        .filter(|p| p.case.m_h == 1000.0 && p.case.k_delta == 1e8)
        .collect();
    assert_eq!(panel.len(), 4);
    // a 200 × 150 pt plot over γ ∈ [0.5, 1], η ∈ [0.15, 1.03]
    let (w, h) = (f64::from(px(200)), f64::from(px(150)));
    let to_pixel = |(g, e): (f64, f64)| {
        (
            ((g - 0.5) / 0.5 * w).round() as i32,
            ((1.03 - e) / 0.88 * h).round() as i32,
        )
    };
    let placed = place_markers(&panel, to_pixel, px(200));
    assert_eq!(placed.len(), 4);
    for (i, a) in placed.iter().enumerate() {
        for b in &placed[..i] {
            // a marker covers neither the other marker nor its value
            for (m, other) in [(a, b), (b, a)] {
                for o in placed_boxes(other) {
                    assert!(!overlap(&placed_boxes(m)[0], &o, 0), "{:?}, {:?}", m.at, o);
                }
            }
        }
        // inside the plot
        assert!(
            a.at.0 + DIAMOND <= px(200) && a.at.0 - DIAMOND >= 0,
            "{:?}",
            a.at
        );
    }
    let moved: Vec<&Placed> = placed.iter().filter(|p| p.callout.is_some()).collect();
    assert_eq!(moved.len(), 3);
    for p in &moved {
        let c = p.callout.unwrap();
        assert_eq!(c.point, to_pixel((p.marker.gamma, p.marker.eta)));
        // below its point by at least a marker's width
        assert!(
            p.at.1 - c.point.1 >= 2 * DIAMOND,
            "{:?} {:?}",
            p.at,
            c.point
        );
    }
    let leaders = moved
        .iter()
        .filter(|p| p.callout.unwrap().leader.is_some())
        .count();
    assert_eq!(leaders, 1);
    // highest η first
    assert!(moved.windows(2).all(|m| m[0].marker.eta >= m[1].marker.eta));
    let svg = fig6_with_points_svg(&curves, &pts, &Fig6Design::PAPER, 504.0).unwrap();
    let text = crate::plots::inspect::texts(&svg);
    for v in ["1.0000", "0.9999", "0.9943"] {
        assert!(text.iter().any(|t| t == v), "{v} not in {text:?}");
    }
}

#[test]
fn bad_points_are_named() {
    let curves = fig6(11).unwrap();
    let mut p = points(&curves)[0];
    p.n = 1.5;
    let e = fig6_with_points_svg(&curves, &[p], &Fig6Design::PAPER, 504.0).unwrap_err();
    assert!(e.contains("no curve of that case and n"), "{e}");
    p.n = 1.0;
    p.eta_fe = f64::NAN;
    let e = fig6_with_points_svg(&curves, &[p], &Fig6Design::PAPER, 504.0).unwrap_err();
    assert!(e.contains("not finite"), "{e}");
}

#[test]
fn the_axis_holds_every_point() {
    let curves = fig6(11).unwrap();
    let axis = EtaAxis::new(&curves, &points(&curves));
    assert!((axis.lo - 0.15).abs() < 1e-12, "{}", axis.lo);
    assert!((axis.top - 1.03).abs() < 1e-12, "{}", axis.top);
    assert!((axis.ticks()[0] - 0.2).abs() < 1e-12);
}

/// Writes /tmp/fig6_points_demo.svg (`cargo test … -- --ignored fig6_points_demo`).
#[test]
#[ignore = "writes a demo figure to /tmp"]
fn fig6_points_demo() {
    let curves = fig6(201).unwrap();
    let svg = fig6_with_points_svg(&curves, &points(&curves), &Fig6Design::PAPER, 504.0).unwrap();
    std::fs::write("/tmp/fig6_points_demo.svg", svg).unwrap();
    std::fs::write(
        "/tmp/fig6_plain_demo.svg",
        fig6_svg(&curves, &Fig6Design::PAPER, 504.0).unwrap(),
    )
    .unwrap();
}
