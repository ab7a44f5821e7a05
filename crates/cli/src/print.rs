//! Printing the reports (text lines, pretty JSON), the progress bar, and the flag conversions
//! shared by the commands.

use std::io::{IsTerminal, Write};
use std::sync::OnceLock;

use flexrig::Error;
use flexrig::testbed::run::Override;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Writes `value` as pretty JSON and a newline to the report.
pub fn print_json(out: &mut dyn Write, value: &serde_json::Value) -> Result<(), Error> {
    let text = serde_json::to_string_pretty(value).expect("a serde_json::Value always serialises");
    writeln!(out, "{text}").map_err(|e| Error::write("<stdout>", e))
}

/// Writes one line of text to the report.
pub fn line(out: &mut dyn Write, text: impl std::fmt::Display) -> Result<(), Error> {
    writeln!(out, "{text}").map_err(|e| Error::write("<stdout>", e))
}

/// The `--set PATH=VALUE` overrides, parsed (an error names the override).
pub fn parse_overrides(set: &[String]) -> Result<Vec<Override>, Error> {
    Ok(set
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>, _>>()?)
}

/// A progress bar on standard error in an indicatif `template`, drawn once the library says how
/// many steps there are, cleared at the end.
pub struct Bar {
    template: &'static str,
    terminal_only: bool,
    bar: OnceLock<ProgressBar>,
}

impl Bar {
    /// A bar drawn as indicatif decides.
    pub fn new(template: &'static str) -> Self {
        Bar {
            template,
            terminal_only: false,
            bar: OnceLock::new(),
        }
    }

    /// A bar drawn only when standard error is a terminal.
    pub fn on_terminal(template: &'static str) -> Self {
        Bar {
            terminal_only: true,
            ..Bar::new(template)
        }
    }
}

impl flexrig::Progress for Bar {
    fn start(&self, total: usize) {
        let style = ProgressStyle::with_template(self.template)
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        let bar = if self.terminal_only {
            let target = if std::io::stderr().is_terminal() {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            };
            ProgressBar::with_draw_target(Some(total as u64), target)
        } else {
            ProgressBar::new(total as u64)
        };
        let _ = self.bar.set(bar.with_style(style));
    }

    fn advance(&self) {
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
        }
    }

    fn finish(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}

/// The severity block of a run or an impact, indented under its report: peak force, peak
/// pressure under each contact-area model, energy, peak acceleration of `struck` (the struck
/// body, in words) and HIC15/HIC36 with their windows.
pub fn print_severity(
    out: &mut dyn Write,
    s: &flexrig::shared::severity::Severity,
    struck: &str,
) -> Result<(), Error> {
    use flexrig::shared::severity::ContactAreaModel;
    line(out, format!("  severity (struck body: {struck})"))?;
    line(
        out,
        format!(
            "    peak force          {:.6} N at t = {:.6} s",
            s.peak_force_n, s.time_of_peak_force_s
        ),
    )?;
    if s.pressure.is_empty() {
        line(
            out,
            "    peak pressure       not assessed (a linear contact law, n ≤ 1, has no contact \
             geometry)",
        )?;
    }
    for p in &s.pressure {
        let name = match p.area_model {
            ContactAreaModel::HertzSphere { .. } => "Hertz sphere",
            ContactAreaModel::ThinLayer { .. } => "thin layer",
            ContactAreaModel::Fixed { .. } => "fixed area",
        };
        line(
            out,
            format!(
                "    peak pressure       {:.4e} Pa (mean {:.4e} Pa), {name} area model",
                p.peak_pa, p.mean_pa
            ),
        )?;
    }
    line(
        out,
        format!(
            "    energy transferred  {:.6e} J (net contact work {:.3e} J)",
            s.energy_transferred_j, s.contact_work_j
        ),
    )?;
    if let (Some(a), Some(g)) = (s.peak_acceleration_mps2, s.peak_acceleration_g) {
        line(
            out,
            format!("    peak acceleration   {a:.6e} m/s² ({g:.4} g)"),
        )?;
    }
    for (name, h) in [("HIC15", s.hic15), ("HIC36", s.hic36)] {
        if let Some(h) = h {
            line(
                out,
                format!(
                    "    {name}               {:.6e} (window {:.6} s to {:.6} s)",
                    h.hic, h.t1_s, h.t2_s
                ),
            )?;
        }
    }
    Ok(())
}
