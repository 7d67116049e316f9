//! Amplitude spectra of uniformly sampled signals with a Hann window (rustfft).

use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

/// The periodic Hann window of length `n`: w_k = (1 − cos(2πk/n))/2.
fn hann(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| 0.5 * (1.0 - (std::f64::consts::TAU * k as f64 / n as f64).cos()))
        .collect()
}

/// Windowed DFT of a complex signal, scaled so a complex exponential of amplitude r on a bin
/// shows |X_k| = r. The mean is removed before windowing (so it does not leak into the lowest
/// bins) and put back exactly in bin 0.
fn windowed_dft(signal: &[Complex64]) -> Vec<Complex64> {
    let n = signal.len();
    let mean = signal.iter().sum::<Complex64>() / n as f64;
    let w = hann(n);
    let gain: f64 = w.iter().sum();
    let mut buf: Vec<Complex64> = signal.iter().zip(&w).map(|(s, w)| (s - mean) * w).collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buf);
    let mut out: Vec<Complex64> = buf.iter().map(|c| c / gain).collect();
    if let Some(dc) = out.first_mut() {
        *dc = mean;
    }
    out
}

/// One-sided amplitude spectrum of a real signal: bins 0..=n/2, a sinusoid of amplitude a on a
/// bin shows a; bin 0 is |mean|.
pub fn real_amplitudes(signal: &[f64]) -> Vec<f64> {
    let n = signal.len();
    let z: Vec<Complex64> = signal.iter().map(|&x| Complex64::new(x, 0.0)).collect();
    let x = windowed_dft(&z);
    (0..=n / 2)
        .map(|k| {
            let a = x[k].norm();
            if k == 0 || 2 * k == n { a } else { 2.0 * a }
        })
        .collect()
}

/// Two-sided amplitude spectrum of the complex whirl x + i y: (bin, amplitude) for bins
/// −(n−1)/2 ..= n/2 in increasing order. A forward circular whirl r·e^{iωτ} shows r at +ω, a
/// backward one at −ω.
pub fn whirl_amplitudes(x: &[f64], y: &[f64]) -> Vec<(i64, f64)> {
    let n = x.len();
    let z: Vec<Complex64> = x
        .iter()
        .zip(y)
        .map(|(&a, &b)| Complex64::new(a, b))
        .collect();
    let spectrum = windowed_dft(&z);
    let lowest = -((n as i64 - 1) / 2);
    (lowest..=(n as i64 / 2))
        .map(|k| (k, spectrum[k.rem_euclid(n as i64) as usize].norm()))
        .collect()
}

/// Indices of the `count` largest local maxima of `amplitudes` (in decreasing amplitude).
pub fn peaks(amplitudes: &[f64], count: usize) -> Vec<usize> {
    let mut local: Vec<usize> = (0..amplitudes.len())
        .filter(|&i| {
            let a = amplitudes[i];
            let left = i == 0 || amplitudes[i - 1] < a;
            let right = i + 1 == amplitudes.len() || amplitudes[i + 1] <= a;
            left && right && a > 0.0
        })
        .collect();
    local.sort_by(|&i, &j| amplitudes[j].total_cmp(&amplitudes[i]));
    local.truncate(count);
    local
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn sinusoid_on_a_bin_shows_its_amplitude() {
        let n = 256;
        let s: Vec<f64> = (0..n)
            .map(|k| 0.7 * (TAU * 8.0 * k as f64 / n as f64).cos() + 0.2)
            .collect();
        let a = real_amplitudes(&s);
        assert!((a[8] - 0.7).abs() < 1e-12);
        assert!((a[0] - 0.2).abs() < 1e-12);
        assert_eq!(peaks(&a, 1), vec![8]);
    }

    #[test]
    fn whirl_separates_directions() {
        let n = 128;
        let (x, y): (Vec<f64>, Vec<f64>) = (0..n)
            .map(|k| {
                let p = TAU * 4.0 * k as f64 / n as f64;
                // forward 0.5 at +4, backward 0.1 at −4
                (0.5 * p.cos() + 0.1 * p.cos(), 0.5 * p.sin() - 0.1 * p.sin())
            })
            .unzip();
        let w = whirl_amplitudes(&x, &y);
        let at = |bin: i64| w.iter().find(|(k, _)| *k == bin).unwrap().1;
        assert!((at(4) - 0.5).abs() < 1e-12);
        assert!((at(-4) - 0.1).abs() < 1e-12);
    }
}
