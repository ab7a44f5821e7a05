//! The lumped two-mass impact, vectorised (exact method), and the paper's Fig. 6.

use flexrig::Error;
use flexrig::lumped::impact::exact;
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use crate::{field_of, input_error, to_py};

/// Parameter sets per parallel chunk.
const CHUNK: usize = 4096;

/// The six outputs of one parameter set.
type Outputs = [f64; 6];

/// The exact (energy) peak of the lumped impact for every parameter set: six float64 arrays of
/// one length (the Python wrapper broadcasts), validated and computed as `flexrig impact
/// --method exact` does. Returns (f_max_n, delta_max_m, indentation_max_m,
/// link_deflection_max_m, mu_kg, impact_energy_j). The first bad set raises InputError naming
/// the argument and its index, e.g. `m_h[3]`. GIL released; parallel over the sets.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[allow(clippy::type_complexity)]
pub fn impact_exact<'py>(
    py: Python<'py>,
    m_h: PyReadonlyArray1<'py, f64>,
    m_eff: PyReadonlyArray1<'py, f64>,
    k_delta: PyReadonlyArray1<'py, f64>,
    k_c: PyReadonlyArray1<'py, f64>,
    n: PyReadonlyArray1<'py, f64>,
    v0: PyReadonlyArray1<'py, f64>,
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
)> {
    let inputs = [
        m_h.as_slice()?,
        m_eff.as_slice()?,
        k_delta.as_slice()?,
        k_c.as_slice()?,
        n.as_slice()?,
        v0.as_slice()?,
    ];
    let len = inputs[0].len();
    if let Some(k) = inputs.iter().position(|a| a.len() != len) {
        return Err(input_error(
            NAMES[k],
            format!(
                "{}: {} values where m_h has {len} (broadcast the arrays first)",
                NAMES[k],
                inputs[k].len()
            ),
        ));
    }
    let mut out: Vec<Outputs> = vec![[0.0; 6]; len];
    let failure: Option<(usize, Error)> = py.detach(|| {
        out.par_chunks_mut(CHUNK)
            .enumerate()
            .filter_map(|(c, chunk)| {
                for (j, slot) in chunk.iter_mut().enumerate() {
                    let i = c * CHUNK + j;
                    let x = |k: usize| inputs[k][i];
                    match exact(x(0), x(1), x(2), x(3), x(4), x(5)) {
                        Ok((model, peak)) => {
                            *slot = [
                                peak.f_max,
                                peak.delta_max,
                                peak.indentation_max,
                                peak.link_deflection_max,
                                model.reduced_mass(),
                                model.impact_energy(),
                            ]
                        }
                        Err(e) => return Some((i, e)),
                    }
                }
                None
            })
            .min_by_key(|(i, _)| *i)
    });
    if let Some((i, e)) = failure {
        return Err(indexed(e, i));
    }
    let column = |k: usize| PyArray1::from_iter(py, out.iter().map(|o| o[k]));
    Ok((
        column(0),
        column(1),
        column(2),
        column(3),
        column(4),
        column(5),
    ))
}

/// The argument names, in order.
const NAMES: [&str; 6] = ["m_h", "m_eff", "k_delta", "k_c", "n", "v0"];

/// The error of set `i`, naming the argument and index (`m_h[3]`) instead of the CLI flag.
fn indexed(e: Error, i: usize) -> PyErr {
    if let Some(flag) = field_of(&e)
        && let Some(name) = NAMES
            .iter()
            .find(|name| flag == format!("--{}", name.replace('_', "-")))
    {
        let field = format!("{name}[{i}]");
        return input_error(&field, e.to_string().replacen(&flag, &field, 1));
    }
    if e.kind() == flexrig::ErrorKind::Input {
        return input_error(&format!("[{i}]"), format!("parameter set {i}: {e}"));
    }
    to_py(e)
}

/// One lumped impact as `flexrig impact --json` reports it, for the same inputs: `m_eff` [kg],
/// or `gamma`, `m_r` [kg] and `m_e` [kg] for m_eff = m_e + γ m_r/3; `method` exact, analytic or
/// ode (with `formulation` auto, indentation or displacement, and `rtol`; the severity's dome
/// radius `dome_radius` [m], ode only). Errors name the keyword argument.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (m_h, m_eff, gamma, m_r, m_e, k_delta, k_c, n, v0, method, formulation, rtol, dome_radius=None))]
pub fn impact_report<'py>(
    py: Python<'py>,
    m_h: f64,
    m_eff: Option<f64>,
    gamma: Option<f64>,
    m_r: Option<f64>,
    m_e: Option<f64>,
    k_delta: f64,
    k_c: f64,
    n: f64,
    v0: f64,
    method: &str,
    formulation: &str,
    rtol: f64,
    dome_radius: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    use flexrig::lumped::impact::ImpactInput;
    // one field for the whole set, so that a vectorised call does not index it
    let m_eff = flexrig::fronts::effective_mass(m_eff, gamma, m_r, m_e)
        .map_err(|e| input_error("m_eff", crate::keywords(&e.to_string())))?;
    let formulation = flexrig::fronts::formulation(formulation).map_err(crate::flag_error)?;
    let method =
        flexrig::fronts::impact_method(method, formulation, rtol).map_err(crate::flag_error)?;
    let input = ImpactInput {
        m_h,
        m_eff,
        k_delta,
        k_c,
        n,
        v0,
    };
    let (report, _) = py
        .detach(|| flexrig::fronts::impact_full_report(&input, method, dome_radius))
        .map_err(crate::flag_error)?;
    crate::convert::json_to_py(py, &report)
}

/// The paper's Fig. 6 (§V, Eq. 15) for any design: η(γ) = f_max(γ)/f_max(1) for every case of
/// the grid (`m_h`, `k_delta`, `m_e` [kg, N/m, kg]: every combination) and n = 1, 2, with
/// `points` samples of γ over [0.5, 1], the design held fixed `m_r` [kg], `k_c` [N/mⁿ], `v0`
/// [m/s]; checked by the library as `flexrig fig6` checks its flags (errors name the keyword).
/// With `out`, fig6.csv and the figure are written there as `flexrig fig6 --out` writes them. A
/// list of dicts: m_h, k_delta, m_e, n, eta_at_2_3 and the arrays gamma and eta.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (points, m_r, k_c, v0, m_h, k_delta, m_e, out, size, format, dpi))]
pub fn fig6<'py>(
    py: Python<'py>,
    points: usize,
    m_r: f64,
    k_c: f64,
    v0: f64,
    m_h: Vec<f64>,
    k_delta: Vec<f64>,
    m_e: Vec<f64>,
    out: Option<std::path::PathBuf>,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    use flexrig::lumped::fig6::{Fig6Design, Fig6Grid, Fig6Options};
    let design = Fig6Design { m_r, k_c, v0 };
    let grid = Fig6Grid { m_h, k_delta, m_e };
    let figures = flexrig::fronts::figure_options(size, &format, dpi).map_err(crate::flag_error)?;
    let curves = py
        .detach(|| match out {
            Some(out) => flexrig::lumped::fig6::run(&Fig6Options {
                out,
                points,
                figures,
                design,
                grid,
            })
            .map(|r| r.curves),
            None => flexrig::lumped::fig6::curves(points, &design, &grid),
        })
        .map_err(crate::flag_error)?;
    curves
        .into_iter()
        .map(|c| {
            let d = PyDict::new(py);
            d.set_item("m_h", c.case.m_h)?;
            d.set_item("k_delta", c.case.k_delta)?;
            d.set_item("m_e", c.case.m_e)?;
            d.set_item("n", c.n)?;
            d.set_item("eta_at_2_3", c.eta_at_2_3)?;
            d.set_item("gamma", PyArray1::from_vec(py, c.gamma))?;
            d.set_item("eta", PyArray1::from_vec(py, c.eta))?;
            Ok(d)
        })
        .collect()
}
