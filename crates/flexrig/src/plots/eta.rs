//! `flexrig eta`'s figure: for each Fig. 6 design case and exponent, η_FE (finite-element CL over
//! rigid CJ, filled) beside the lumped model's η(2/3) (hollow) on one η axis, one row per case.

use flexrig_impact::eta::EtaRow;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, LABEL_PT, PALETTE, TICK_PT, TITLE_PT, err, font, px, render, sci_label, stroke,
    text, text_width_pt,
};

/// Height per row \[pt\].
const ROW: u32 = 12;
/// Title, legend and axis \[pt\].
const FRAME: u32 = 80;

/// The row label of `r`: its case and exponent.
fn row_label(r: &EtaRow) -> String {
    format!(
        "{} kg, {} N/m, {} kg, n = {}",
        r.case.m_h,
        sci_label(r.case.k_delta),
        r.case.m_e,
        r.n
    )
}

/// The dot plot of `rows` (as `flexrig eta` prints them), titled with `joint`, at the printed
/// width `width_pt` \[pt\].
pub fn eta_svg(rows: &[EtaRow], joint: &str, width_pt: f64) -> Result<String, String> {
    let height = FRAME + ROW * rows.len() as u32;
    let x_max = rows
        .iter()
        .flat_map(|r| [r.eta_fe, r.eta_lumped_2_3])
        .fold(1.0_f64, f64::max);
    let x_max = (x_max * 10.0).ceil() / 10.0 + 0.05;
    let labels: Vec<String> = rows.iter().map(row_label).collect();
    let label_w = labels
        .iter()
        .map(|l| text_width_pt(l, TICK_PT))
        .fold(text_width_pt("m_h, k_δ, m_e, n", TICK_PT), f64::max)
        + 8.0;
    render((width_pt.round() as u32, height), |root| {
        let w = width_pt.round() as i32;
        let title = if text_width_pt(
            "η = f_max(CL)/f_max(CJ): finite elements vs the lumped η(2/3), held joint",
            TITLE_PT,
        ) < width_pt
        {
            format!("η = f_max(CL)/f_max(CJ): finite elements vs the lumped η(2/3), {joint} joint")
        } else {
            format!("η = f_max(CL)/f_max(CJ), {joint} joint")
        };
        root.draw(&Text::new(
            title,
            (px(w / 2), px(3)),
            text(TITLE_PT, BLACK, HPos::Center, VPos::Top),
        ))
        .map_err(err)?;
        // legend
        let y = px(20);
        let x0 = px(4);
        root.draw(&Circle::new((x0 + px(3), y), px(3), PALETTE[0].filled()))
            .map_err(err)?;
        let fe = "finite elements η_FE";
        root.draw(&Text::new(
            fe,
            (x0 + px(9), y),
            text(LABEL_PT, BLACK, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
        let x1 = x0 + px((text_width_pt(fe, LABEL_PT) + 22.0) as i32);
        root.draw(&Circle::new(
            (x1 + px(3), y),
            px(3),
            stroke(PALETTE[1], 1.25),
        ))
        .map_err(err)?;
        root.draw(&Text::new(
            "lumped model, η(2/3)",
            (x1 + px(9), y),
            text(LABEL_PT, BLACK, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
        let body = root.margin(px(40), px(4), px(4), px(10));
        body.draw(&Text::new(
            "m_h, k_δ, m_e, n",
            (px(label_w as i32 - 6), -px(2)),
            text(TICK_PT, GREY, HPos::Right, VPos::Bottom),
        ))
        .map_err(err)?;
        let n = rows.len() as f64;
        let mut chart = ChartBuilder::on(&body)
            .x_label_area_size(px(26))
            .y_label_area_size(px(label_w as i32))
            .build_cartesian_2d(0.0..x_max, -0.5..(n - 0.5))
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .bold_line_style(stroke(GRID, 0.75))
            .axis_style(stroke(BLACK, 0.75))
            .set_all_tick_mark_size(px(2))
            .x_desc("η")
            .axis_desc_style(font(LABEL_PT))
            .label_style(font(TICK_PT))
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
                stroke(GREY, 0.75),
            ))
            .map_err(err)?;
        for (i, r) in rows.iter().enumerate() {
            let y = n - 1.0 - i as f64;
            chart
                .draw_series(LineSeries::new(
                    [(r.eta_fe, y), (r.eta_lumped_2_3, y)],
                    stroke(GRID, 1.5),
                ))
                .map_err(err)?;
            chart
                .draw_series([Circle::new(
                    (r.eta_lumped_2_3, y),
                    px(3),
                    stroke(PALETTE[1], 1.25),
                )])
                .map_err(err)?;
            chart
                .draw_series([Circle::new((r.eta_fe, y), px(3), PALETTE[0].filled())])
                .map_err(err)?;
        }
        Ok(())
    })
}
