//! Virtual sensors as on the test bed (paper Fig. 8): encoders on both axes, an accelerometer on
//! the operator block and one on the load, and the force sensor between the load and the dome
//! (the dome is massless here, so it reads the contact force). Sampled at a fixed rate,
//! independent of the step, by linear interpolation between step ends; the accelerations are
//! those of the step containing the sample (velocity change over the step).

use serde::Serialize;

/// One sample of every sensor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SensorSample {
    /// Time \[s\].
    pub t: f64,
    /// Operator encoder: pendulum angle from the vertical, positive towards the robot \[rad\].
    pub operator_angle_rad: f64,
    /// Robot encoder: angle of the robot axis \[rad\] (CL: the shaft the link is clamped to, 0
    /// without a drive).
    pub robot_angle_rad: f64,
    /// Lateral tip deflection of the link (CJ: L sin θ; CL: beam tip v) \[m\].
    pub link_tip_deflection_m: f64,
    /// Operator block accelerometer, along the strike direction (world y) [m/s²].
    pub operator_accel_mps2: f64,
    /// Load accelerometer, along the strike direction (world y) [m/s²].
    pub load_accel_mps2: f64,
    /// Force sensor between load and dome \[N\].
    pub force_n: f64,
    /// Contact indentation δ \[m\] (linear between step ends like the force; 0 outside contact).
    pub indentation_m: f64,
}

/// The state of the measured quantities at a step end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// Time \[s\].
    pub t: f64,
    /// Operator angle \[rad\].
    pub operator_angle: f64,
    /// Robot axis angle \[rad\].
    pub robot_angle: f64,
    /// Link tip deflection \[m\].
    pub tip_deflection: f64,
    /// Operator block velocity along y [m/s].
    pub operator_velocity: f64,
    /// Load velocity along y [m/s].
    pub load_velocity: f64,
    /// Contact force \[N\].
    pub force: f64,
    /// Contact indentation \[m\] (0 outside contact).
    pub indentation: f64,
}

/// Samples the readings at `rate` Hz.
///
/// **Lean sampling** ([`Sampler::lean`]): the samples of the free swing (taken on an
/// integrator's dense output, [`Sampler::record_deferred`]) are not computed when they are
/// taken; the sampler keeps the dense output instead (a [`DeferredSpan`]) and computes a
/// sample on demand — those a recorder asks for as the run goes, those the severity needs at
/// the end ([`crate::severity::of_sampler`]), or all of them ([`Sampler::materialize`]). A
/// sample computed on demand is the one the full sampler computes at the same time, bit for
/// bit (the same index, the same time `k × period`, the same function of the same dense
/// output). Every other sample (the steps', the contact's) is taken as it comes.
#[derive(Debug)]
pub struct Sampler {
    period: f64,
    next_index: u64,
    samples: Vec<SensorSample>,
    /// Lean: the index of every sample in `samples` (empty when not lean: the samples are
    /// then every index from 0 in order).
    indices: Vec<u64>,
    lean: bool,
    deferred: Vec<DeferredSpan>,
}

/// The sensor samples of one stretch of the free swing, computed on demand.
pub struct DeferredSpan {
    /// First sample index.
    pub first: u64,
    /// One past the last sample index.
    pub end: u64,
    /// An upper bound of |operator accelerometer| over the span's samples [m/s²].
    pub operator_accel_bound: f64,
    eval: Box<dyn Fn(f64) -> SensorSample + Send + Sync>,
}

impl std::fmt::Debug for DeferredSpan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DeferredSpan")
            .field("first", &self.first)
            .field("end", &self.end)
            .field("operator_accel_bound", &self.operator_accel_bound)
            .finish_non_exhaustive()
    }
}

impl DeferredSpan {
    /// The sample at time `t` \[s\] (inside the span).
    pub fn sample(&self, t: f64) -> SensorSample {
        (self.eval)(t)
    }
}

impl Sampler {
    /// A sampler at `rate_hz` > 0 starting at t = 0.
    pub fn new(rate_hz: f64) -> Self {
        Sampler {
            period: 1.0 / rate_hz,
            next_index: 0,
            samples: Vec::new(),
            indices: Vec::new(),
            lean: false,
            deferred: Vec::new(),
        }
    }

    /// A lean sampler at `rate_hz` > 0 (see [`Sampler`]).
    pub fn lean(rate_hz: f64) -> Self {
        Sampler {
            lean: true,
            ..Sampler::new(rate_hz)
        }
    }

    /// Whether the sampler is lean.
    pub fn is_lean(&self) -> bool {
        self.lean
    }

    /// The sampling period \[s\].
    pub fn period(&self) -> f64 {
        self.period
    }

    /// How many samples the run has taken (computed or deferred).
    pub fn count(&self) -> u64 {
        self.next_index
    }

    fn push(&mut self, index: u64, sample: SensorSample) {
        if self.lean {
            self.indices.push(index);
        }
        self.samples.push(sample);
    }

    /// Records every sample time in (a.t, b.t] (and t = 0 at the first call).
    pub fn record_step(&mut self, a: &Reading, b: &Reading) {
        let dt = b.t - a.t;
        if !(dt > 0.0) {
            return;
        }
        let operator_accel = (b.operator_velocity - a.operator_velocity) / dt;
        let load_accel = (b.load_velocity - a.load_velocity) / dt;
        loop {
            let t = self.next_index as f64 * self.period;
            if t > b.t {
                break;
            }
            self.next_index += 1;
            if t < a.t {
                continue;
            }
            let w = (t - a.t) / dt;
            let lerp = |x: f64, y: f64| x + (y - x) * w;
            self.push(
                self.next_index - 1,
                SensorSample {
                    t,
                    operator_angle_rad: lerp(a.operator_angle, b.operator_angle),
                    robot_angle_rad: lerp(a.robot_angle, b.robot_angle),
                    link_tip_deflection_m: lerp(a.tip_deflection, b.tip_deflection),
                    operator_accel_mps2: operator_accel,
                    load_accel_mps2: load_accel,
                    force_n: lerp(a.force, b.force),
                    indentation_m: lerp(a.indentation, b.indentation),
                },
            );
        }
    }

    /// Records every sample time in (`t_a`, `t_b`] (and t = 0 at the first call) from `at`, the
    /// exact state at a time (e.g. an integrator's dense output): no interpolation between the
    /// step's ends.
    pub fn record_exact(&mut self, t_a: f64, t_b: f64, mut at: impl FnMut(f64) -> SensorSample) {
        if !(t_b > t_a) {
            return;
        }
        loop {
            let t = self.next_index as f64 * self.period;
            if t > t_b {
                break;
            }
            self.next_index += 1;
            if t < t_a {
                continue;
            }
            self.push(self.next_index - 1, at(t));
        }
    }

    /// Records every sample time in (`t_a`, `t_b`] (and t = 0 at the first call) from `at`, as
    /// [`Sampler::record_exact`]; a lean sampler keeps `at` instead (with `accel_bound`, an
    /// upper bound of |operator accelerometer| over the stretch) and computes now only the
    /// samples `wanted` asks for (called in time order with each sample time; `None`: none).
    /// Returns the range of sample indices of the stretch.
    pub fn record_deferred(
        &mut self,
        t_a: f64,
        t_b: f64,
        at: impl Fn(f64) -> SensorSample + Send + Sync + 'static,
        accel_bound: f64,
        wanted: Option<&mut dyn FnMut(f64) -> bool>,
    ) -> std::ops::Range<u64> {
        if !self.lean {
            let first = self.next_index;
            self.record_exact(t_a, t_b, at);
            return first..self.next_index;
        }
        if !(t_b > t_a) {
            return self.next_index..self.next_index;
        }
        // The indices record_exact would visit: from next_index, those with t_a <= t <= t_b,
        // by the same comparisons of the same products.
        let period = self.period;
        let time = |k: u64| k as f64 * period;
        let mut first = self.next_index;
        if time(first) < t_a {
            // jump close, then walk to the exact first index with time >= t_a
            let guess = ((t_a / self.period).floor() as u64)
                .saturating_sub(1)
                .max(first);
            first = guess;
            while time(first) < t_a {
                first += 1;
            }
        }
        let mut end = first;
        if time(end) <= t_b {
            let guess = ((t_b / self.period).floor() as u64)
                .saturating_sub(1)
                .max(end);
            end = guess;
            while time(end) <= t_b {
                end += 1;
            }
        }
        self.next_index = end;
        if let Some(wanted) = wanted {
            for k in first..end {
                let t = time(k);
                if wanted(t) {
                    self.push(k, at(t));
                }
            }
        }
        if end > first {
            self.deferred.push(DeferredSpan {
                first,
                end,
                operator_accel_bound: accel_bound,
                eval: Box::new(at),
            });
        }
        first..end
    }

    /// The samples computed so far with their indices (a full sampler: every sample, its
    /// index its position).
    pub fn computed(&self) -> impl Iterator<Item = (u64, &SensorSample)> + '_ {
        self.samples.iter().enumerate().map(|(i, s)| {
            let k = if self.lean { self.indices[i] } else { i as u64 };
            (k, s)
        })
    }

    /// How many samples the run took: those computed and those deferred (what a full
    /// sampler holds).
    pub fn taken(&self) -> usize {
        if !self.lean {
            return self.samples.len();
        }
        let spans = &self.deferred;
        let in_span = |k: u64| spans.iter().any(|d| d.first <= k && k < d.end);
        let deferred: u64 = spans.iter().map(|d| d.end - d.first).sum();
        deferred as usize + self.computed().filter(|(k, _)| !in_span(*k)).count()
    }

    /// The deferred spans (none for a full sampler).
    pub fn deferred(&self) -> &[DeferredSpan] {
        &self.deferred
    }

    /// The sample of index `k`, computed or deferred (`None` past the last).
    pub fn sample_at(&self, k: u64) -> Option<SensorSample> {
        if !self.lean {
            return self.samples.get(k as usize).copied();
        }
        if let Ok(i) = self.indices.binary_search(&k) {
            return Some(self.samples[i]);
        }
        let span = self.deferred.iter().find(|d| d.first <= k && k < d.end)?;
        Some(span.sample(k as f64 * self.period))
    }

    /// The samples with times in [`t_lo`, `t_hi`] \[s\] (and a few just outside), the deferred
    /// ones computed: the full sampler's there.
    pub fn samples_between(&self, t_lo: f64, t_hi: f64) -> Vec<SensorSample> {
        if !self.lean {
            return self
                .samples
                .iter()
                .filter(|s| s.t >= t_lo && s.t <= t_hi)
                .copied()
                .collect();
        }
        if !(t_hi >= t_lo) {
            return Vec::new();
        }
        let first = ((t_lo / self.period).floor().max(0.0) as u64).saturating_sub(1);
        let last = ((t_hi / self.period).ceil().max(0.0) as u64 + 1).min(self.next_index);
        (first..last).filter_map(|k| self.sample_at(k)).collect()
    }

    /// Every sample of the run in order, the deferred ones computed: what the full sampler
    /// holds, bit for bit.
    pub fn materialize(&self) -> Vec<SensorSample> {
        if !self.lean {
            return self.samples.clone();
        }
        (0..self.next_index)
            .filter_map(|k| self.sample_at(k))
            .collect()
    }

    /// The samples so far.
    pub fn samples(&self) -> &[SensorSample] {
        &self.samples
    }

    /// Takes the samples.
    pub fn into_samples(self) -> Vec<SensorSample> {
        self.samples
    }
}
