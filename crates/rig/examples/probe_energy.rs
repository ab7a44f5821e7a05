use flexrig_contact::Materials;
use flexrig_rig::{Frame, Recorder, RigError, RunOptions, Scene, Simulation, StepOutcome};
struct P {
    n: usize,
    last_t: f64,
    e0: Option<f64>,
}
impl Recorder for P {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        self.n += 1;
        let e0 = *self.e0.get_or_insert(f.energy);
        if f.outcome != StepOutcome::Advanced || f.t - self.last_t > 0.1 {
            self.last_t = f.t;
            if std::env::var("QUIET").is_err() {
                println!(
                    "t {:.6} dt {:.2e} {:?} E-E0 {:.3e} op {:.4} {:.4} contact {:?}",
                    f.t,
                    f.dt,
                    f.outcome,
                    f.energy - e0,
                    f.operator.angle,
                    f.operator.rate,
                    f.contact.map(|c| c.force)
                );
            }
        }
        Ok(())
    }
}
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let scene = Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap();
    let r = Simulation::new(
        &scene,
        RunOptions {
            beam_rho_inf: std::env::var("RHO").map_or(1.0, |s| s.parse().unwrap()),
            ..RunOptions::default()
        },
    )
    .unwrap()
    .run(&mut P {
        n: 0,
        last_t: 0.0,
        e0: None,
    });
    match r {
        Ok(s) => println!(
            "contacts {} E_end/E0-1 {:.3e} steps {}",
            s.contacts.len(),
            s.energy_final_j / s.energy_initial_j - 1.0,
            s.steps
        ),
        Err(e) => println!("{e}"),
    }
}
