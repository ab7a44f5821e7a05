//! A banded matrix and its LU factorisation with partial pivoting (LAPACK `gbtf2` scheme).
//!
//! The beam's node-ordered DOFs give a half-bandwidth of 5 (one element couples 6 consecutive
//! DOFs), so factorisation costs O(n·kl·(kl + ku)) and a solve O(n·(2kl + ku)): linear in the
//! number of elements. faer 0.24 has no banded solver and its general sparse LU/Cholesky carries
//! a symbolic/permutation overhead that dominates at the sizes the rig uses (≈ 100 DOFs, 20 µs
//! per step budget), hence this small dedicated kernel; dense/sparse faer is used for the
//! eigenproblem ([`crate::modal`]).

use crate::BeamError;

/// A square banded matrix with `kl` sub- and `ku` super-diagonals, stored by columns with `kl`
/// extra rows for the fill-in of pivoting.
#[derive(Debug, Clone, PartialEq)]
pub struct BandMatrix {
    n: usize,
    kl: usize,
    ku: usize,
    ld: usize,
    data: Vec<f64>,
    pivots: Vec<usize>,
    factored: bool,
}

impl BandMatrix {
    /// A zero `n`×`n` matrix with `kl` sub- and `ku` super-diagonals.
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        let ld = 2 * kl + ku + 1;
        BandMatrix {
            n,
            kl,
            ku,
            ld,
            data: vec![0.0; ld * n],
            pivots: vec![0; n],
            factored: false,
        }
    }
    /// Dimension n.
    pub fn n(&self) -> usize {
        self.n
    }
    /// Zeroes every entry (keeps the allocation).
    pub fn clear(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
        self.factored = false;
    }
    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        j * self.ld + self.kl + self.ku + i - j
    }
    /// Entry (i, j); zero outside the band.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i + self.ku >= j && i <= j + self.kl {
            self.data[self.idx(i, j)]
        } else {
            0.0
        }
    }
    /// Adds `value` to entry (i, j), which must lie inside the band.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        debug_assert!(
            i + self.ku >= j && i <= j + self.kl,
            "({i},{j}) outside the band"
        );
        let k = self.idx(i, j);
        self.data[k] += value;
    }
    /// y = A x (before factorisation).
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            *yi = (lo..=hi).map(|j| self.data[self.idx(i, j)] * x[j]).sum();
        }
    }
    /// LU factorisation in place with partial pivoting. `what` names the matrix in the error
    /// raised on a (numerically) zero pivot.
    pub fn factorize(&mut self, what: &str) -> Result<(), BeamError> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        let scale = self.data.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tiny = scale * 1e-14;
        for j in 0..n {
            let last = (j + kl).min(n - 1);
            let mut p = j;
            let mut best = self.data[self.idx(j, j)].abs();
            for i in j + 1..=last {
                let v = self.data[self.idx(i, j)].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best.is_nan() || best <= tiny {
                return Err(BeamError::Singular {
                    what: what.to_string(),
                    dof: j,
                    hint: "the structure is a mechanism (e.g. a pinned root without a torsion \
                           spring under a static load) or the solution diverged"
                        .into(),
                });
            }
            self.pivots[j] = p;
            let cend = (j + ku + kl).min(n - 1);
            if p != j {
                for c in j..=cend {
                    let (a, b) = (self.idx(j, c), self.idx(p, c));
                    self.data.swap(a, b);
                }
            }
            let d = self.data[self.idx(j, j)];
            for i in j + 1..=last {
                let k = self.idx(i, j);
                self.data[k] /= d;
            }
            let nl = last - j;
            if nl > 0 {
                // column j's multipliers (rows j+1..=last) are contiguous, and so is each
                // column c's segment of the same rows: split the storage and update by slices
                let lstart = self.idx(j + 1, j);
                let (head, tail) = self.data.split_at_mut((j + 1) * self.ld);
                let l = &head[lstart..lstart + nl];
                for c in j + 1..=cend {
                    let base = (c - j - 1) * self.ld + self.kl + self.ku + j - c;
                    let ajc = tail[base];
                    if ajc != 0.0 {
                        let seg = &mut tail[base + 1..base + 1 + nl];
                        for (x, li) in seg.iter_mut().zip(l) {
                            *x -= li * ajc;
                        }
                    }
                }
            }
        }
        self.factored = true;
        Ok(())
    }
    /// Solves A x = b in place (after [`BandMatrix::factorize`]).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        assert!(self.factored, "BandMatrix::solve_in_place before factorize");
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for j in 0..n {
            let p = self.pivots[j];
            if p != j {
                b.swap(p, j);
            }
            let bj = b[j];
            if bj != 0.0 {
                for i in j + 1..=(j + kl).min(n - 1) {
                    b[i] -= self.data[self.idx(i, j)] * bj;
                }
            }
        }
        for j in (0..n).rev() {
            b[j] /= self.data[self.idx(j, j)];
            let bj = b[j];
            if bj != 0.0 {
                for i in j.saturating_sub(kl + ku)..j {
                    b[i] -= self.data[self.idx(i, j)] * bj;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_nonsymmetric_band_system_needing_pivots() {
        let n = 40;
        let (kl, ku) = (3, 2);
        let mut a = BandMatrix::zeros(n, kl, ku);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                // small diagonal forces pivoting
                let v = if i == j {
                    1e-3 * (i as f64 + 1.0)
                } else {
                    ((i * 7 + j * 3) % 11) as f64 - 5.0
                };
                a.add(i, j, v);
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut b = vec![0.0; n];
        a.mul_vec(&x, &mut b);
        a.factorize("test").unwrap();
        a.solve_in_place(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-10, "{i}: {} vs {}", b[i], x[i]);
        }
    }

    #[test]
    fn singular_matrix_is_an_error_not_a_panic() {
        let mut a = BandMatrix::zeros(3, 1, 1);
        a.add(0, 0, 1.0);
        a.add(1, 1, 0.0);
        a.add(2, 2, 1.0);
        assert!(matches!(
            a.factorize("K"),
            Err(BeamError::Singular { dof: 1, .. })
        ));
    }
}
