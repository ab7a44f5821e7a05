//! `flexrig eta`'s figure: for each Fig. 6 design case and exponent, η_FE (finite-element CL over
//! rigid CJ, filled) beside the lumped model's η(2/3) (hollow) on one η axis, one row per case.

use flexrig_impact::eta::EtaRow;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{GREY, GRID, PALETTE, err, font, px, render, stroke, text};

/// Nominal width of the figure [px]; the height grows with the rows.
const WIDTH: u32 = 900;
/// Height per row [px].
const ROW: u32 = 26;

/// The dot plot of `rows` (as `flexrig eta` prints them), titled with `joint`.
pub fn eta_svg(rows: &[EtaRow], joint: &str) -> Result<String, String> {
    let height = 150 + ROW * rows.len() as u32;
    let x_max = rows
        .iter()
        .flat_map(|r| [r.eta_fe, r.eta_lumped_2_3])
        .fold(1.0_f64, f64::max);
    let x_max = (x_max * 10.0).ceil() / 10.0 + 0.05;
    render((WIDTH, height), |root| {
        let title = format!(
            "η = f_max(CL)/f_max(CJ): finite elements (filled) vs the lumped model's η(2/3) (hollow); {joint} joint"
        );
        root.draw(&Text::new(
            title,
            (px(WIDTH as i32 / 2), px(10)),
            text(14.0, BLACK, HPos::Center, VPos::Top),
        ))
        .map_err(err)?;
        let body = root.margin(px(40), px(20), px(10), px(20));
        let n = rows.len() as f64;
        let mut chart = ChartBuilder::on(&body)
            .x_label_area_size(px(40))
            .y_label_area_size(px(300))
            .build_cartesian_2d(0.0..x_max, -0.5..(n - 0.5))
            .map_err(err)?;
        let labels: Vec<String> = rows
            .iter()
            .map(|r| {
                format!(
                    "m_h {} kg, k_δ {:e} N/m, m_e {} kg, n = {}",
                    r.case.m_h, r.case.k_delta, r.case.m_e, r.n
                )
            })
            .collect();
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .bold_line_style(GRID)
            .x_desc("η")
            .axis_desc_style(font(14.0))
            .label_style(font(12.0))
            .x_labels(8)
            .x_label_formatter(&|v| format!("{v:.1}"))
            .y_labels(rows.len())
            .y_label_formatter(&|v| {
                let i = (n - 1.0 - v).round();
                if (v - v.round()).abs() < 1e-9 && i >= 0.0 && (i as usize) < labels.len() {
                    labels[i as usize].clone()
                } else {
                    String::new()
                }
            })
            .draw()
            .map_err(err)?;
        // η = 1: CL and CJ equal
        chart
            .draw_series(LineSeries::new(
                [(1.0, -0.5), (1.0, n - 0.5)],
                stroke(GREY, 1.0),
            ))
            .map_err(err)?;
        for (i, r) in rows.iter().enumerate() {
            let y = n - 1.0 - i as f64;
            chart
                .draw_series(LineSeries::new(
                    [(r.eta_fe, y), (r.eta_lumped_2_3, y)],
                    stroke(GRID, 2.0),
                ))
                .map_err(err)?;
            chart
                .draw_series([Circle::new(
                    (r.eta_lumped_2_3, y),
                    px(5),
                    stroke(PALETTE[1], 2.0),
                )])
                .map_err(err)?;
            chart
                .draw_series([Circle::new((r.eta_fe, y), px(5), PALETTE[0].filled())])
                .map_err(err)?;
        }
        Ok(())
    })
}
