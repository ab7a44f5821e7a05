//! SVG figures (plotters), rendered to a string so the caller can write them atomically.

use flexrig_lumped::fig6::{EtaCurve, GAMMA_RANGE};
use plotters::prelude::*;
use plotters::series::DashedLineSeries;

/// Colour of the n = 2 curves (solid), as in the paper.
const BLUE: RGBColor = RGBColor(31, 119, 180);
/// Colour of the n = 1 curves (dashed), as in the paper.
const ORANGE: RGBColor = RGBColor(255, 127, 14);

/// The paper's Fig. 6: one panel per design case, η over γ, n = 2 solid and n = 1 dashed, η(2/3)
/// marked and labelled. `curves` holds both exponents of each case.
pub fn fig6_svg(curves: &[EtaCurve]) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1600, 820)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (title, body) = root.split_vertically(50);
        title
            .titled(
                "Fig. 6: peak-force ratio η = f_max(γ)/f_max(1) — n = 2 solid, n = 1 dashed (m_r = 10 kg, k_c = 1e8, v0 = 2 m/s)",
                ("sans-serif", 20),
            )
            .map_err(|e| e.to_string())?;
        let panels = body.split_evenly((2, 4));
        let mut cases: Vec<_> = curves.iter().map(|c| c.case).collect();
        cases.dedup();
        for (panel, case) in panels.iter().zip(&cases) {
            let of_case: Vec<&EtaCurve> = curves.iter().filter(|c| c.case == *case).collect();
            let y_min = of_case
                .iter()
                .flat_map(|c| c.eta.iter().copied())
                .fold(1.0, f64::min);
            let y_lo = ((y_min - 0.02) * 20.0).floor() / 20.0;
            let mut chart = ChartBuilder::on(panel)
                .caption(
                    format!(
                        "m_h={} kg, k_δ={:e} N/m, m_e={} kg",
                        case.m_h, case.k_delta, case.m_e
                    ),
                    ("sans-serif", 15),
                )
                .margin(12)
                .x_label_area_size(36)
                .y_label_area_size(48)
                .build_cartesian_2d(GAMMA_RANGE.0..GAMMA_RANGE.1, y_lo..1.01)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc("γ")
                .y_desc("η")
                .x_labels(6)
                .y_labels(6)
                .draw()
                .map_err(|e| e.to_string())?;
            for c in &of_case {
                let points: Vec<(f64, f64)> =
                    c.gamma.iter().copied().zip(c.eta.iter().copied()).collect();
                let colour = if c.n == 1.0 { ORANGE } else { BLUE };
                let style = colour.stroke_width(2);
                if c.n == 1.0 {
                    chart
                        .draw_series(DashedLineSeries::new(points, 8, 5, style))
                        .map_err(|e| e.to_string())?;
                } else {
                    chart
                        .draw_series(LineSeries::new(points, style))
                        .map_err(|e| e.to_string())?;
                }
                let mark = (2.0 / 3.0, c.eta_at_2_3);
                let label_at = if c.n == 1.0 { (-150, -22) } else { (8, 6) };
                chart
                    .draw_series(std::iter::once(
                        EmptyElement::at(mark)
                            + Circle::new((0, 0), 4, colour.filled())
                            + Text::new(
                                format!("η(2/3)={:.3} (n={})", c.eta_at_2_3, c.n),
                                label_at,
                                ("sans-serif", 13).into_font().color(&colour),
                            ),
                    ))
                    .map_err(|e| e.to_string())?;
            }
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// The paper's Fig. 9: (a) peak force of CJ and CL against the aluminium and the iron operator,
/// mean ± 95 % CI; (b) the light-load case. `groups` are named by scene (`cj_aluminium`, ...).
pub fn fig9_svg(groups: &[crate::commands::experiment::GroupStats]) -> Result<String, String> {
    let find = |name: &str| groups.iter().find(|g| g.scene == name);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1100, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (left, right) = root.split_horizontally(700);
        // (area, title, [(x label, scene suffix)]).
        type Cases<'a> = [(&'a str, &'a str); 2];
        let panels: [(&DrawingArea<_, _>, &str, Cases); 2] = [
            (
                &left,
                "(a) test bed: m_e = 412 g, mean ± 95 % CI",
                [
                    ("aluminium operator 398 g", "aluminium"),
                    ("iron operator 4008 g", "iron"),
                ],
            ),
            (
                &right,
                "(b) light load m_e = 0.1 kg",
                [("aluminium operator", "light_load"), ("", "")],
            ),
        ];
        for (area, title, cases) in panels {
            let cases: Vec<_> = cases.iter().filter(|c| !c.1.is_empty()).collect();
            let top = cases
                .iter()
                .flat_map(|c| [find(&format!("cj_{}", c.1)), find(&format!("cl_{}", c.1))])
                .flatten()
                .map(|g| g.mean_peak_force_n + g.ci95_n)
                .fold(0.0, f64::max)
                * 1.15;
            let mut chart = ChartBuilder::on(area)
                .caption(title, ("sans-serif", 18))
                .margin(15)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(0.0..(3.0 * cases.len() as f64), 0.0..top.max(1.0))
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .disable_x_mesh()
                .x_labels(0)
                .y_desc("peak impact force [N]")
                .draw()
                .map_err(|e| e.to_string())?;
            for (i, (label, key)) in cases.iter().enumerate() {
                let x0 = 3.0 * i as f64;
                for (j, (design, colour)) in [("cj", ORANGE), ("cl", BLUE)].iter().enumerate() {
                    let Some(g) = find(&format!("{design}_{key}")) else {
                        continue;
                    };
                    let (a, b) = (x0 + 0.5 + j as f64, x0 + 1.4 + j as f64);
                    let m = g.mean_peak_force_n;
                    chart
                        .draw_series(std::iter::once(Rectangle::new(
                            [(a, 0.0), (b, m)],
                            colour.filled(),
                        )))
                        .map_err(|e| e.to_string())?;
                    let c = 0.5 * (a + b);
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(c, m - g.ci95_n), (c, m + g.ci95_n)],
                            BLACK.stroke_width(2),
                        )))
                        .map_err(|e| e.to_string())?;
                    chart
                        .draw_series(std::iter::once(Text::new(
                            format!("{} {:.1} N", design.to_uppercase(), m),
                            (a, m + g.ci95_n + 0.03 * top),
                            ("sans-serif", 13),
                        )))
                        .map_err(|e| e.to_string())?;
                }
                chart
                    .draw_series(std::iter::once(Text::new(
                        label.to_string(),
                        (x0 + 0.5, -0.06 * top),
                        ("sans-serif", 14),
                    )))
                    .map_err(|e| e.to_string())?;
            }
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// Log–log work–precision plot: error against run time, one line per method.
pub fn work_precision_svg(
    title: &str,
    rows: &[&crate::commands::bench::Row],
) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.error > 0.0 && r.seconds > 0.0)
            .map(|r| (r.seconds, r.error))
            .collect();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for (x, y) in &points {
            x0 = x0.min(*x);
            x1 = x1.max(*x);
            y0 = y0.min(*y);
            y1 = y1.max(*y);
        }
        if points.is_empty() {
            (x0, x1, y0, y1) = (1e-6, 1.0, 1e-12, 1.0);
        }
        let mut chart = ChartBuilder::on(&root)
            .caption(format!("work–precision: {title}"), ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 * 0.7..x1 * 1.4).log_scale(),
                (y0 * 0.3..y1 * 3.0).log_scale(),
            )
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("run time [s]")
            .y_desc("relative error")
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()
            .map_err(|e| e.to_string())?;
        let mut methods: Vec<&str> = Vec::new();
        for r in rows {
            if !methods.contains(&r.method.as_str()) {
                methods.push(&r.method);
            }
        }
        for (i, method) in methods.iter().enumerate() {
            let colour = Palette99::pick(i).to_rgba();
            let series: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.method == *method && r.error > 0.0)
                .map(|r| (r.seconds, r.error))
                .collect();
            if series.is_empty() {
                continue;
            }
            chart
                .draw_series(LineSeries::new(series.clone(), colour.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(method.to_string())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 15, y)], colour.stroke_width(2))
                });
            chart
                .draw_series(
                    series
                        .into_iter()
                        .map(|p| Circle::new(p, 3, colour.filled())),
                )
                .map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
