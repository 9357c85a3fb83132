//! A measured height profile (issue 31): two columns `x, h` read from a file, at any spacing and
//! in any order, smoothed to a stated tolerance.
//!
//! The file: one sample a line, `x` and `h` (rod lengths; `x` in the lab frame, the foot at
//! `x = 0` when `d = 0`; `h` relative to `eta`) separated by a comma, a semicolon, tabs or
//! spaces; `#` starts a comment; a first line that is not two numbers is a header. The samples
//! are sorted by `x`; two at the same `x` are an error.
//!
//! The smoothing (Reinsch 1967, in the form of Green & Silverman 1994, §2.3): the natural cubic
//! spline `g` minimizing `Σ (h_i − g(x_i))² + α ∫ g''² dx`, with the largest `α` (the smoothest
//! spline) whose every value stays within the tolerance of its sample, `max_i |g(x_i) − h_i| ≤
//! tol`. For a given `α` the second derivatives `γ` at the interior samples solve the
//! pentadiagonal system `(R + α QᵀQ) γ = Qᵀ h` and `g = h − α Q γ` (`Q`, `R` the spline's band
//! matrices); `α` is found by bisection in `log α` (to a factor 1 + 1e-9), the largest deviation
//! being nearly monotone in `α` (the bisection keeps the last `α` within the tolerance whatever).
//! `tol = 0` gives the interpolating spline. Noise of amplitude `ε` in the heights needs
//! `tol ≳ ε`; then the profile's slopes and curvatures are those of the smooth surface.

use crate::limits;
use crate::VibrissaError;
use std::path::Path;

fn bad(reason: String) -> VibrissaError {
    VibrissaError::InvalidTable {
        name: "surface.file".into(),
        reason,
    }
}

/// The samples of a profile file, sorted by `x` (see the module docs).
pub(crate) fn read_profile(path: &Path) -> Result<(Vec<f64>, Vec<f64>), VibrissaError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| bad(format!("cannot read {}: {e}", path.display())))?;
    parse_profile(&text).map_err(|r| bad(format!("{}: {r}", path.display())))
}

/// Why a profile's text is refused (the line or samples it names).
#[derive(Debug, thiserror::Error)]
pub(crate) enum ProfileTextError {
    #[error("line {line}: x = {x}, h = {h} must be finite")]
    NotFinite { line: usize, x: f64, h: f64 },
    #[error("line {line}: '{text}' is not two numbers x, h (one sample a line)")]
    NotTwoNumbers { line: usize, text: String },
    #[error("x = {x} appears twice (lines {first} and {second}): one height per position")]
    Twice { x: f64, first: usize, second: usize },
    #[error("{count} samples; a profile needs {need} (a spline through them)")]
    Count { count: usize, need: String },
}

/// The samples of a profile's text, sorted by `x`; the error says which line.
pub(crate) fn parse_profile(text: &str) -> Result<(Vec<f64>, Vec<f64>), ProfileTextError> {
    let mut rows: Vec<(f64, f64, usize)> = Vec::new();
    let mut header = false;
    for (i, line, nums) in numeric_lines(text) {
        match nums {
            Some(v) if v.len() == 2 => {
                if !(v[0].is_finite() && v[1].is_finite()) {
                    return Err(ProfileTextError::NotFinite {
                        line: i + 1,
                        x: v[0],
                        h: v[1],
                    });
                }
                rows.push((v[0], v[1], i + 1));
            }
            None if rows.is_empty() && !header => header = true,
            _ => {
                return Err(ProfileTextError::NotTwoNumbers {
                    line: i + 1,
                    text: line.to_string(),
                })
            }
        }
    }
    rows.sort_by(|p, q| p.0.total_cmp(&q.0));
    for w in rows.windows(2) {
        if w[0].0 == w[1].0 {
            return Err(ProfileTextError::Twice {
                x: w[0].0,
                first: w[0].2,
                second: w[1].2,
            });
        }
    }
    if !limits::PROFILE_POINTS.contains_count(rows.len()) {
        return Err(ProfileTextError::Count {
            count: rows.len(),
            need: limits::PROFILE_POINTS.text(6),
        });
    }
    Ok(rows.iter().map(|r| (r.0, r.1)).unzip())
}

/// The lines of a table's text that are not empty after their `#` comment is cut: the line's
/// number (from 0), its text, and its numbers if every field is one (fields separated by a
/// comma, a semicolon, tabs or spaces). Shared by the profile files and the dynamic drag's foot
/// tables.
pub(crate) fn numeric_lines(text: &str) -> impl Iterator<Item = (usize, &str, Option<Vec<f64>>)> {
    text.lines().enumerate().filter_map(|(i, line)| {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            return None;
        }
        let nums = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|c| !c.is_empty())
            .map(|c| c.parse::<f64>().ok())
            .collect();
        Some((i, line, nums))
    })
}

/// The band matrices of the smoothing spline on `x`: `R` (diagonal, first off-diagonal) and `Q`
/// (each interior sample `j` has the column `(1/h_{j−1}, −1/h_{j−1} − 1/h_j, 1/h_j)` on rows
/// `j − 1, j, j + 1`).
struct Bands {
    r0: Vec<f64>,
    r1: Vec<f64>,
    q: Vec<[f64; 3]>,
}

impl Bands {
    fn new(x: &[f64]) -> Bands {
        let n = x.len();
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let m = n - 2;
        let mut b = Bands {
            r0: vec![0.0; m],
            r1: vec![0.0; m],
            q: vec![[0.0; 3]; m],
        };
        for c in 0..m {
            let (h0, h1) = (h[c], h[c + 1]);
            b.r0[c] = (h0 + h1) / 3.0;
            b.r1[c] = h1 / 6.0;
            b.q[c] = [1.0 / h0, -1.0 / h0 - 1.0 / h1, 1.0 / h1];
        }
        b
    }

    /// The smoothed values `g = y − α Q γ` for `α`.
    fn smooth(&self, y: &[f64], alpha: f64) -> Vec<f64> {
        let m = self.r0.len();
        let q = &self.q;
        // (QᵀQ) bands: column c has rows c, c+1, c+2 of y's index
        let qq0 = |c: usize| q[c][0] * q[c][0] + q[c][1] * q[c][1] + q[c][2] * q[c][2];
        let qq1 = |c: usize| q[c][1] * q[c + 1][0] + q[c][2] * q[c + 1][1];
        let qq2 = |c: usize| q[c][2] * q[c + 2][0];
        let (mut d, mut l1, mut l2) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        for c in 0..m {
            let a0 = self.r0[c] + alpha * qq0(c);
            let a1 = if c + 1 < m {
                self.r1[c] + alpha * qq1(c)
            } else {
                0.0
            };
            let a2 = if c + 2 < m { alpha * qq2(c) } else { 0.0 };
            let mut dc = a0;
            if c >= 1 {
                dc -= l1[c - 1] * l1[c - 1] * d[c - 1];
            }
            if c >= 2 {
                dc -= l2[c - 2] * l2[c - 2] * d[c - 2];
            }
            d[c] = dc;
            let mut e = a1;
            if c >= 1 {
                e -= l1[c - 1] * l2[c - 1] * d[c - 1];
            }
            l1[c] = e / dc;
            l2[c] = a2 / dc;
        }
        // Qᵀ y, then L z = Qᵀ y, D, Lᵀ γ = z
        let mut z: Vec<f64> = (0..m)
            .map(|c| q[c][0] * y[c] + q[c][1] * y[c + 1] + q[c][2] * y[c + 2])
            .collect();
        for c in 0..m {
            if c >= 1 {
                z[c] -= l1[c - 1] * z[c - 1];
            }
            if c >= 2 {
                z[c] -= l2[c - 2] * z[c - 2];
            }
        }
        for c in 0..m {
            z[c] /= d[c];
        }
        for c in (0..m).rev() {
            if c + 1 < m {
                z[c] -= l1[c] * z[c + 1];
            }
            if c + 2 < m {
                z[c] -= l2[c] * z[c + 2];
            }
        }
        let mut g = y.to_vec();
        for c in 0..m {
            for (k, qk) in q[c].iter().enumerate() {
                g[c + k] -= alpha * qk * z[c];
            }
        }
        g
    }
}

/// The heights of the smoothest spline within `tol` of every sample `(x_i, y_i)` (see the
/// module docs), and its `α`.
pub(crate) fn smooth(x: &[f64], y: &[f64], tol: f64) -> (Vec<f64>, f64) {
    if tol <= 0.0 || x.len() < 3 {
        return (y.to_vec(), 0.0);
    }
    let b = Bands::new(x);
    let dev = |g: &[f64]| {
        g.iter()
            .zip(y)
            .map(|(g, y)| (g - y).abs())
            .fold(0.0, f64::max)
    };
    let within = |alpha: f64| -> Option<Vec<f64>> {
        let g = b.smooth(y, alpha);
        (dev(&g) <= tol && g.iter().all(|v| v.is_finite())).then_some(g)
    };
    // α's natural scale: the mean spacing cubed (R ~ h, QᵀQ ~ 1/h²)
    let span = x[x.len() - 1] - x[0];
    let scale = (span / (x.len() - 1) as f64).powi(3);
    let (mut good, mut best) = (0.0, y.to_vec());
    let mut bad = f64::NAN;
    // bracket: up in decades from 1e-12 of the scale
    for e in -12..=40 {
        let a = scale * 10f64.powi(e);
        match within(a) {
            Some(g) => {
                good = a;
                best = g;
            }
            None => {
                bad = a;
                break;
            }
        }
    }
    if good == 0.0 || bad.is_nan() {
        // nothing smoother fits (or even the smoothest does)
        return (best, good);
    }
    let (mut lo, mut hi) = (good.ln(), bad.ln());
    while hi - lo > 1e-9 {
        let mid = 0.5 * (lo + hi);
        match within(mid.exp()) {
            Some(g) => {
                lo = mid;
                best = g;
            }
            None => hi = mid,
        }
    }
    (best, lo.exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The band solve against a dense one: `g = y − α Q γ` with `(R + α QᵀQ) γ = Qᵀ y`.
    #[test]
    fn band_solve_matches_dense_elimination() {
        let x = [0.0, 0.1, 0.25, 0.3, 0.5, 0.55, 0.8];
        let y = [0.0, 0.02, -0.01, 0.03, 0.0, 0.01, -0.02];
        let alpha = 3e-4;
        let n = x.len();
        let m = n - 2;
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let mut q = vec![vec![0.0; m]; n];
        let mut r = vec![vec![0.0; m]; m];
        for c in 0..m {
            q[c][c] = 1.0 / h[c];
            q[c + 1][c] = -1.0 / h[c] - 1.0 / h[c + 1];
            q[c + 2][c] = 1.0 / h[c + 1];
            r[c][c] = (h[c] + h[c + 1]) / 3.0;
            if c + 1 < m {
                r[c][c + 1] = h[c + 1] / 6.0;
                r[c + 1][c] = h[c + 1] / 6.0;
            }
        }
        let mut a = vec![vec![0.0; m + 1]; m];
        for i in 0..m {
            for j in 0..m {
                a[i][j] = r[i][j] + alpha * (0..n).map(|k| q[k][i] * q[k][j]).sum::<f64>();
            }
            a[i][m] = (0..n).map(|k| q[k][i] * y[k]).sum();
        }
        // Gauss–Jordan
        for p in 0..m {
            let piv = a[p][p];
            let row: Vec<f64> = a[p].iter().map(|v| v / piv).collect();
            for (i, ai) in a.iter_mut().enumerate() {
                if i == p {
                    ai.clone_from(&row);
                    continue;
                }
                let f = ai[p];
                for (v, r) in ai.iter_mut().zip(&row) {
                    *v -= f * r;
                }
            }
        }
        let gamma: Vec<f64> = (0..m).map(|i| a[i][m]).collect();
        let g = Bands::new(&x).smooth(&y, alpha);
        for k in 0..n {
            let want = y[k] - alpha * (0..m).map(|c| q[k][c] * gamma[c]).sum::<f64>();
            assert!((g[k] - want).abs() < 1e-15, "{k}: {} {want}", g[k]);
        }
    }

    #[test]
    fn files_are_read_in_any_order_and_refused_with_the_line() {
        let (x, h) =
            parse_profile("x, h\n# a comment\n0.2 0.01\n0.0,0.0\n\n0.1;-0.01 # c\n").unwrap();
        assert_eq!((x, h), (vec![0.0, 0.1, 0.2], vec![0.0, -0.01, 0.01]));
        let e = parse_profile("0 0\n0.1 0.2\n0.1 0.3\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("lines 2 and 3"), "{e}");
        let e = parse_profile("0 0\n0.1 0.2 0.3\n").unwrap_err().to_string();
        assert!(e.contains("line 2"), "{e}");
        let e = parse_profile("0 0\n0.1 0.2\n").unwrap_err().to_string();
        assert!(e.contains("2 samples"), "{e}");
    }
}
