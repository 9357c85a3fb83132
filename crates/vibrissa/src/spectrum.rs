//! The amplitude spectrum of a signal sampled in time (issue 32: the ringing of the moment at
//! the foot, `m_base(t)`, of `dynamics::free` and `dynamics::drag`).
//!
//! Method: the samples (times strictly increasing, not necessarily evenly spaced: the dynamic
//! drag shortens the steps where its events fall) are interpolated linearly onto `N` evenly
//! spaced times spanning the record, `N` the smallest power of two at least the number of
//! samples (and at least [`MIN_SAMPLES`]); their mean is removed; a Hann window
//! `w_n = ½(1 − cos(2πn/N))` is applied; the discrete Fourier transform (radix-2 FFT) gives
//! `X_k`, `k = 0 … N/2`, at the frequencies `f_k = k/(N h)` (`h` the even spacing; cycles per
//! time unit of the input). The amplitude is one-sided and corrected for the window's coherent
//! gain, `A_k = 2|X_k| / Σw_n` (`|X_k|/Σw_n` at `k = 0` and `k = N/2`), so a sinusoid
//! `a cos(2πft)` whose frequency falls on a bin shows the peak `a` there; between bins the Hann
//! window's peak is lower by at most 15 % and its neighbour bin carries the rest. The
//! resolution is one bin, `1/(N h)` ≈ the reciprocal of the record's duration.

use crate::VibrissaError;
use serde::Serialize;

/// Fewest samples of a spectrum.
pub const MIN_SAMPLES: usize = 4;

/// Most evenly spaced points of a spectrum (`N`, a power of two): 2²⁴, 16.8 million.
pub const MAX_POINTS: usize = 1 << 24;

/// An amplitude spectrum (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Spectrum {
    /// Frequencies `f_k = k/(N h)`, `k = 0 … N/2` (cycles per time unit of the input).
    pub frequency: Vec<f64>,
    /// One-sided amplitudes `A_k` (the unit of the signal).
    pub amplitude: Vec<f64>,
    /// The number `N` of evenly spaced points.
    pub points: usize,
    /// Their spacing `h` in time.
    pub spacing: f64,
    /// The mean removed.
    pub mean: f64,
}

impl Spectrum {
    /// The frequency of the largest amplitude (`k ≥ 1`).
    pub fn peak(&self) -> f64 {
        let mut best = (0.0, f64::NEG_INFINITY);
        for (f, a) in self.frequency.iter().zip(&self.amplitude).skip(1) {
            if *a > best.1 {
                best = (*f, *a);
            }
        }
        best.0
    }

    /// The width of one bin, `1/(N h)`.
    pub fn bin(&self) -> f64 {
        1.0 / (self.points as f64 * self.spacing)
    }
}

/// The amplitude spectrum of the samples `y` at the times `t` (see the module docs). Errors:
/// lengths that differ, fewer than [`MIN_SAMPLES`] samples or more than [`MAX_POINTS`], times
/// not strictly increasing, values that are not finite.
pub fn amplitude_spectrum(t: &[f64], y: &[f64]) -> Result<Spectrum, VibrissaError> {
    if t.len() != y.len() {
        return Err(VibrissaError::range(
            "values of the spectrum",
            y.len() as f64,
            format!("as many as the times, {}", t.len()),
        ));
    }
    if t.len() < MIN_SAMPLES || t.len() > MAX_POINTS {
        return Err(VibrissaError::range(
            "samples of the spectrum",
            t.len() as f64,
            format!("[{MIN_SAMPLES}, {MAX_POINTS}]"),
        ));
    }
    if let Some(i) = (0..t.len()).find(|&i| !t[i].is_finite() || !y[i].is_finite()) {
        return Err(VibrissaError::range(
            "sample of the spectrum",
            if t[i].is_finite() { y[i] } else { t[i] },
            "finite",
        ));
    }
    if let Some(w) = t.windows(2).find(|w| w[1] <= w[0]) {
        return Err(VibrissaError::range(
            "time of the spectrum's samples",
            w[1],
            format!("greater than the one before, {}", w[0]),
        ));
    }
    let n = t.len().next_power_of_two();
    let (t0, t1) = (t[0], t[t.len() - 1]);
    let h = (t1 - t0) / (n - 1) as f64;
    // linear interpolation onto the even times
    let mut even = Vec::with_capacity(n);
    let mut j = 0;
    for k in 0..n {
        let tk = if k == n - 1 { t1 } else { t0 + k as f64 * h };
        while j + 2 < t.len() && t[j + 1] < tk {
            j += 1;
        }
        let u = ((tk - t[j]) / (t[j + 1] - t[j])).clamp(0.0, 1.0);
        even.push(y[j] + u * (y[j + 1] - y[j]));
    }
    let mean = even.iter().sum::<f64>() / n as f64;
    let mut re = Vec::with_capacity(n);
    let mut sum_w = 0.0;
    for (k, v) in even.iter().enumerate() {
        let w = 0.5 * (1.0 - (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos());
        sum_w += w;
        re.push(w * (v - mean));
    }
    let mut im = vec![0.0; n];
    fft(&mut re, &mut im);
    let half = n / 2;
    let mut frequency = Vec::with_capacity(half + 1);
    let mut amplitude = Vec::with_capacity(half + 1);
    for k in 0..=half {
        let scale = if k == 0 || k == half { 1.0 } else { 2.0 };
        frequency.push(k as f64 / (n as f64 * h));
        amplitude.push(scale * re[k].hypot(im[k]) / sum_w);
    }
    Ok(Spectrum {
        frequency,
        amplitude,
        points: n,
        spacing: h,
        mean,
    })
}

/// In-place radix-2 FFT, `X_k = Σ x_n e^{−2πikn/N}` (`N` a power of two).
fn fft(re: &mut [f64], im: &mut [f64]) {
    let n = re.len();
    // bit-reversal permutation
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= n {
        let ang = -2.0 * std::f64::consts::PI / len as f64;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                // the twiddle computed directly (no recurrence: no drift over long transforms)
                let (s, c) = (ang * k as f64).sin_cos();
                let (a, b) = (start + k, start + k + len / 2);
                let (xr, xi) = (re[b] * c - im[b] * s, re[b] * s + im[b] * c);
                re[b] = re[a] - xr;
                im[b] = im[a] - xi;
                re[a] += xr;
                im[a] += xi;
            }
        }
        len <<= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The FFT against the defining sum (a direct DFT) on a random-looking signal: 1e-12.
    #[test]
    fn fft_is_the_dft() {
        let n = 64;
        let x: Vec<f64> = (0..n)
            .map(|i| ((i * i * 7 + 3) % 17) as f64 - 8.0)
            .collect();
        let (mut re, mut im) = (x.clone(), vec![0.0; n]);
        fft(&mut re, &mut im);
        for k in 0..n {
            let (mut sr, mut si) = (0.0, 0.0);
            for (j, v) in x.iter().enumerate() {
                let a = -2.0 * PI * (k * j) as f64 / n as f64;
                sr += v * a.cos();
                si += v * a.sin();
            }
            assert!(
                (re[k] - sr).abs() < 1e-12 && (im[k] - si).abs() < 1e-12,
                "{k}"
            );
        }
    }

    /// A sinusoid on a bin, plus a constant, sampled unevenly: the peak is at its frequency with
    /// its amplitude (the Hann window's coherent gain corrected; 1e-3 from the linear
    /// interpolation of samples 0.01 apart), the mean is removed.
    #[test]
    fn a_sinusoid_peaks_at_its_frequency_with_its_amplitude() {
        // 1024 samples over [0, 1023 h]: the even points are t = k h, the bins k/(1024 h)
        let h = 0.01;
        let t: Vec<f64> = (0..1024)
            .map(|i| {
                let wobble = if i % 3 == 1 && i < 1023 { 0.3 * h } else { 0.0 };
                i as f64 * h + wobble
            })
            .collect();
        let f = 10.0 / (1024.0 * h);
        let y: Vec<f64> = t
            .iter()
            .map(|t| 2.0 + 0.7 * (2.0 * PI * f * t).cos())
            .collect();
        let s = amplitude_spectrum(&t, &y).unwrap();
        assert_eq!(s.points, 1024);
        assert!((s.peak() - f).abs() < 1e-12, "{} {f}", s.peak());
        assert!((s.bin() - 1.0 / (1024.0 * h)).abs() < 1e-12);
        assert!((s.amplitude[10] - 0.7).abs() < 1e-3, "{}", s.amplitude[10]);
        assert!((s.mean - 2.0).abs() < 1e-3, "{}", s.mean);
        assert!(s.amplitude[0] < 1e-3, "{}", s.amplitude[0]);
    }

    /// Bad input is refused.
    #[test]
    fn bad_samples_are_refused() {
        assert!(amplitude_spectrum(&[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0]).is_err());
        assert!(amplitude_spectrum(&[0.0, 1.0, 1.0, 2.0], &[0.0; 4]).is_err());
        assert!(amplitude_spectrum(&[0.0, 1.0, 2.0, 3.0], &[0.0, f64::NAN, 0.0, 0.0]).is_err());
        assert!(amplitude_spectrum(&[0.0, 1.0, 2.0, 3.0], &[0.0; 3]).is_err());
    }
}
