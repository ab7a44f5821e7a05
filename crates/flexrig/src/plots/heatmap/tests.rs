use super::*;

fn grid(n: usize, lo: f64, hi: f64) -> Vec<f64> {
    (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect()
}

fn map<'a>(xs: &'a [f64], ys: &'a [f64], values: &'a [Option<f64>]) -> HeatMap<'a> {
    HeatMap {
        title: "synthetic map",
        x_label: "m_e/m_r",
        y_label: "k_δ/k_c",
        xs,
        ys,
        values,
        scale: ColorScale::Sequential { lo: -3.0, hi: 3.0 },
        value_label: "log10 x + log10 y",
        outline: None,
    }
}

fn synthetic(xs: &[f64], ys: &[f64]) -> Vec<Option<f64>> {
    ys.iter()
        .flat_map(|y| xs.iter().map(move |x| Some(x.log10() + y.log10())))
        .collect()
}

#[test]
fn edges_are_geometric_midpoints() {
    let e = log_edges(&[1.0, 10.0, 100.0], "xs").unwrap();
    let want = [-0.5, 0.5, 1.5, 2.5];
    assert!(e.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12));
    assert_eq!(log_edges(&[10.0], "xs").unwrap(), vec![0.5, 1.5]);
}

#[test]
fn a_30_by_30_map_renders() {
    let xs = grid(30, 1e-2, 1e2);
    let ys = grid(30, 1e-3, 1e2);
    let values = synthetic(&xs, &ys);
    let mask: Vec<bool> = values.iter().map(|v| v.unwrap() > 0.5).collect();
    let mut m = map(&xs, &ys, &values);
    m.outline = Some((&mask, "value > 0.5"));
    let svg = heatmaps_svg(&["figure title here".to_string()], &[m], 504.0).unwrap();
    assert!(svg.starts_with("<svg width=\"7in\""));
    assert!(svg.contains("figure title here"));
    assert!(svg.contains("synthetic map"));
    assert!(svg.contains("value &gt; 0.5") || svg.contains("value > 0.5"));
    assert!(svg.contains("10⁻²") && svg.contains("10²"));
    // values run from −5 to 4, beyond the scale's ±3: both ends are clamped
    assert!(svg.contains("≥ 3") && svg.contains("≤ −3"));
    assert!(!svg.contains("no value"));
}

#[test]
fn every_scale_renders_side_by_side() {
    let xs = grid(12, 1e-1, 1e1);
    let ys = grid(8, 1.0, 1e4);
    let values = synthetic(&xs, &ys);
    let positive: Vec<Option<f64>> = values.iter().map(|v| v.map(|v| 10f64.powf(v))).collect();
    let mut a = map(&xs, &ys, &values);
    a.title = "diverging";
    a.scale = ColorScale::Diverging {
        centre: 2.0,
        span: 1.5,
    };
    let mut b = map(&xs, &ys, &positive);
    b.title = "log";
    b.scale = ColorScale::Log { lo: 1e-1, hi: 1e5 };
    let svg = heatmaps_svg(
        &["three".to_string()],
        &[map(&xs, &ys, &values), a, b],
        504.0,
    )
    .unwrap();
    assert!(svg.starts_with("<svg width=\"7in\""));
    assert!(svg.contains("diverging") && svg.contains(">\nlog\n<"));
}

#[test]
fn a_map_without_values_renders() {
    let xs = grid(5, 1.0, 1e4);
    let ys = grid(4, 1.0, 1e3);
    let values = vec![None; 20];
    let svg = heatmaps_svg(&["empty".to_string()], &[map(&xs, &ys, &values)], 504.0).unwrap();
    assert!(svg.contains("no value"));
}

#[test]
fn bad_input_is_named() {
    let xs = grid(4, 1.0, 1e3);
    let ys = grid(3, 1.0, 1e2);
    let values = synthetic(&xs, &ys);
    let e = heatmaps_svg(&["t".to_string()], &[map(&xs, &ys, &values[1..])], 504.0).unwrap_err();
    assert!(
        e.contains("values has 11 entries, expected nx·ny = 4·3 = 12"),
        "{e}"
    );
    let e = heatmaps_svg(&["t".to_string()], &[map(&[], &ys, &[])], 504.0).unwrap_err();
    assert!(e.contains("empty grid: xs"), "{e}");
    let e = heatmaps_svg(&["t".to_string()], &[map(&xs, &[], &[])], 504.0).unwrap_err();
    assert!(e.contains("empty grid: ys"), "{e}");
    let bad_x = [0.0, 1.0, 2.0, 3.0];
    let e = heatmaps_svg(&["t".to_string()], &[map(&bad_x, &ys, &values)], 504.0).unwrap_err();
    assert!(e.contains("xs must be finite and > 0"), "{e}");
    let bad_y = [1.0, -1.0, 2.0];
    let e = heatmaps_svg(&["t".to_string()], &[map(&xs, &bad_y, &values)], 504.0).unwrap_err();
    assert!(e.contains("ys must be finite and > 0"), "{e}");
    let e = heatmaps_svg(
        &["t".to_string()],
        &[map(&xs, &[1.0, 3.0, 2.0], &values)],
        504.0,
    )
    .unwrap_err();
    assert!(e.contains("ys must be strictly ascending"), "{e}");
    let mask = [true; 5];
    let mut m = map(&xs, &ys, &values);
    m.outline = Some((&mask, "region"));
    let e = heatmaps_svg(&["t".to_string()], &[m], 504.0).unwrap_err();
    assert!(e.contains("outline mask has 5 entries"), "{e}");
    for scale in [
        ColorScale::Sequential { lo: 1.0, hi: 1.0 },
        ColorScale::Sequential { lo: 2.0, hi: 1.0 },
        ColorScale::Log { lo: 0.0, hi: 1.0 },
        ColorScale::Diverging {
            centre: 0.0,
            span: 0.0,
        },
    ] {
        let mut m = map(&xs, &ys, &values);
        m.scale = scale;
        let e = heatmaps_svg(&["t".to_string()], &[m], 504.0).unwrap_err();
        assert!(e.contains("bad colour scale"), "{e}");
    }
    assert!(heatmaps_svg(&["t".to_string()], &[], 504.0).is_err());
}

#[test]
fn labels_and_colours() {
    assert_eq!(plain(0.25), "0.25");
    assert_eq!(plain(-1.5), "−1.5");
    assert_eq!(plain(3.0), "3");
    assert_eq!(plain(1e5), "10⁵");
    assert_eq!(plain(1e-17), "0");
    assert_eq!(log_label(2.0), "10²");
    // between decades the number itself, never `2·10⁰`
    assert_eq!(log_label(2f64.log10()), "2");
    assert_eq!(log_label(0.05f64.log10()), "0.05");
    assert_eq!(log_label(3e5f64.log10()), "3·10⁵");
    assert_eq!(log_ticks(-2.1, 2.1), vec![-2.0, -1.0, 0.0, 1.0, 2.0]);
    assert_eq!(log_ticks(0.1, 0.9).len(), 2);
    let d = ColorScale::Diverging {
        centre: 1.0,
        span: 0.5,
    };
    assert_eq!(d.colour(1.0), Some(WHITE));
    assert_eq!(d.colour(f64::NAN), None);
    assert_eq!(d.side(2.0), 1);
    let labels: Vec<String> = d.ticks().iter().map(|c| d.label(*c)).collect();
    assert_eq!(labels, ["0.6", "0.8", "1", "1.2", "1.4"]);
    let l = ColorScale::Log { lo: 1e-2, hi: 1e2 };
    assert_eq!(l.side(0.0), -1);
    assert_eq!(l.colour(1e9), Some(RGBColor(253, 231, 37)));
}

/// Writes /tmp/heatmap_demo.svg (`cargo test … -- --ignored heatmap_demo`).
#[test]
#[ignore = "writes a demo figure to /tmp"]
fn heatmap_demo() {
    let xs = grid(30, 1e-3, 1e1);
    let ys = grid(30, 1e-6, 1e0);
    let eta: Vec<Option<f64>> = ys
        .iter()
        .flat_map(|y| {
            xs.iter().map(move |x| {
                let (lx, ly) = (x.log10(), y.log10());
                (lx + ly > -8.0).then(|| 1.0 / (1.0 + 10f64.powf(-0.6 * (lx + 0.5 * ly + 2.0))))
            })
        })
        .collect();
    let ratio: Vec<Option<f64>> = eta
        .iter()
        .zip(ys.iter().flat_map(|y| xs.iter().map(move |x| (x, y))))
        .map(|(e, (x, y))| e.map(|e| e / (0.8 + 0.05 * (x.log10() - y.log10()).sin())))
        .collect();
    let peak: Vec<Option<f64>> = ys
        .iter()
        .flat_map(|y| {
            xs.iter()
                .map(move |x| Some(3e3 * (x * 1e3).sqrt() * y.powf(0.2)))
        })
        .collect();
    let mask: Vec<bool> = ratio
        .iter()
        .map(|r| r.is_some_and(|r| (r - 1.0).abs() < 0.05))
        .collect();
    let maps = [
        HeatMap {
            title: "(a) η_FE",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &eta,
            scale: ColorScale::Sequential { lo: 0.2, hi: 1.0 },
            value_label: "η_FE",
            outline: None,
        },
        HeatMap {
            title: "(b) η_FE / η lumped",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &ratio,
            scale: ColorScale::Diverging {
                centre: 1.0,
                span: 0.25,
            },
            value_label: "η_FE / η(2/3)",
            outline: Some((&mask, "lumped model within 5 %")),
        },
        HeatMap {
            title: "(c) f_max",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &peak,
            scale: ColorScale::Log { lo: 1e2, hi: 1e4 },
            value_label: "f_max [N]",
            outline: None,
        },
    ];
    let svg = heatmaps_svg(
        &["Demo: synthetic data over the (m_e/m_r, k_δ/k_c) plane".to_string()],
        &maps,
        504.0,
    )
    .unwrap();
    std::fs::write("/tmp/heatmap_demo.svg", svg).unwrap();
}
