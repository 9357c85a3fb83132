//! The natural cubic spline through a table `(x_i, y_i)`, `x` strictly increasing: C², its
//! second derivatives `m_i` at the nodes the solution of the tridiagonal system
//!
//! ```text
//!     h_{i−1}/6 m_{i−1} + (h_{i−1} + h_i)/3 m_i + h_i/6 m_{i+1}
//!         = (y_{i+1} − y_i)/h_i − (y_i − y_{i−1})/h_{i−1},     m_0 = m_{n−1} = 0
//! ```
//!
//! (Thomas' algorithm; the system is diagonally dominant, so it needs no pivoting). Shared by the
//! table surfaces (`surface`) and the foot's path of the dynamic drag (`dyndrag`).

/// The second derivatives at the nodes of the natural spline through `(x, y)` (`x` strictly
/// increasing, as long as `y`, at least 2 entries: two give the straight line).
pub(crate) fn natural_moments(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut m = vec![0.0; n];
    let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
    for i in 1..n.saturating_sub(1) {
        let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let a = h0 / 6.0;
        let b = (h0 + h1) / 3.0;
        let cc = h1 / 6.0;
        let r = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
        let den = b - a * c[i - 1];
        c[i] = cc / den;
        d[i] = (r - a * d[i - 1]) / den;
    }
    for i in (1..n.saturating_sub(1)).rev() {
        m[i] = d[i] - c[i] * m[i + 1];
    }
    m
}

/// The spline's value, slope and second derivative at `t` (beyond the table: its end pieces
/// continued).
pub(crate) fn jet(xs: &[f64], y: &[f64], m: &[f64], t: f64) -> (f64, f64, f64) {
    let n = xs.len();
    let i = xs.partition_point(|&u| u <= t).clamp(1, n - 1) - 1;
    let hh = xs[i + 1] - xs[i];
    let (a, b) = ((xs[i + 1] - t) / hh, (t - xs[i]) / hh);
    let v = a * y[i]
        + b * y[i + 1]
        + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * hh * hh / 6.0;
    let d = (y[i + 1] - y[i]) / hh
        + (-(3.0 * a * a - 1.0) * m[i] + (3.0 * b * b - 1.0) * m[i + 1]) * hh / 6.0;
    let dd = a * m[i] + b * m[i + 1];
    (v, d, dd)
}

#[cfg(test)]
mod tests {
    use super::{jet, natural_moments};

    /// A cubic with zero second derivative at both ends is not in general a natural spline,
    /// but a straight line and a parabola's interior are checked: the spline through a line is
    /// the line, and through `t²` on a fine table its interior second derivative is 2 to the
    /// end effect's decay (it falls by about `2 − √3` per node from each end).
    #[test]
    fn lines_and_parabolas() {
        let x = [0.0, 0.3, 1.0, 1.5];
        let y: Vec<f64> = x.iter().map(|t| 2.0 - 3.0 * t).collect();
        let m = natural_moments(&x, &y);
        for t in [-0.5, 0.1, 0.7, 1.2, 2.0] {
            let (v, d, dd) = jet(&x, &y, &m, t);
            // (rounding only: the moments of a line are 0 to a few ulps)
            let e = [(v - (2.0 - 3.0 * t)).abs(), (d + 3.0).abs(), dd.abs()];
            assert!(e.iter().all(|e| *e < 1e-13), "{t}: {e:?}");
        }
        let x: Vec<f64> = (0..=40).map(|i| i as f64 / 40.0).collect();
        let y: Vec<f64> = x.iter().map(|t| t * t).collect();
        let m = natural_moments(&x, &y);
        assert!((m[20] - 2.0).abs() < 1e-9, "{}", m[20]);
        let (v, d, _) = jet(&x, &y, &m, 0.5123);
        assert!((v - 0.5123f64.powi(2)).abs() < 1e-12 && (d - 2.0 * 0.5123).abs() < 1e-9);
        // two points: the straight line (no interior node)
        assert_eq!(natural_moments(&[0.0, 1.0], &[0.0, 2.0]), vec![0.0, 0.0]);
    }
}
