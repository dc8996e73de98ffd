//! Least-squares fits and simple statistics used by the analyses.

use super::AnalyzeError;

/// A straight line `y = intercept + slope x` fitted by least squares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineFit {
    /// Slope (units of y per unit of x).
    pub slope: f64,
    /// Standard error of the slope (same units); 0 for two points.
    pub slope_err: f64,
    /// Intercept (units of y).
    pub intercept: f64,
    /// Points used.
    pub n: usize,
    /// Root-mean-square residual (units of y).
    pub rms: f64,
}

impl LineFit {
    /// The fitted value at `x`.
    pub fn at(&self, x: f64) -> f64 {
        self.intercept + self.slope * x
    }
}

/// Fit `y = a + b x` to the points; Err with fewer than two points or no spread in x.
pub fn fit_line(points: &[(f64, f64)]) -> Result<LineFit, AnalyzeError> {
    let n = points.len();
    if n < 2 {
        return Err(AnalyzeError::Fit(format!(
            "{n} point(s): a line needs at least 2"
        )));
    }
    let nf = n as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
    let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return Err(AnalyzeError::Fit("all points at the same x".into()));
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let ssr: f64 = points
        .iter()
        .map(|p| (p.1 - intercept - slope * p.0).powi(2))
        .sum();
    let slope_err = if n > 2 {
        (ssr / (nf - 2.0) / sxx).sqrt()
    } else {
        0.0
    };
    Ok(LineFit {
        slope,
        slope_err,
        intercept,
        n,
        rms: (ssr / nf).sqrt(),
    })
}

/// Fit a line, then drop the points whose residual exceeds `k` standard deviations and refit,
/// until none is dropped. Returns the fit and the points kept.
pub fn fit_line_clipped(
    points: &[(f64, f64)],
    k: f64,
) -> Result<(LineFit, Vec<(f64, f64)>), AnalyzeError> {
    let mut kept = points.to_vec();
    loop {
        let fit = fit_line(&kept)?;
        let before = kept.len();
        let limit = k * fit.rms;
        if limit > 0.0 {
            kept.retain(|p| (p.1 - fit.at(p.0)).abs() <= limit);
        }
        if kept.len() == before || kept.len() < 3 {
            return Ok((fit_line(&kept)?, kept));
        }
    }
}

/// A power law `y = prefactor x^exponent`, fitted as a line in log-log space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerFit {
    /// The exponent (dimensionless).
    pub exponent: f64,
    /// Its standard error.
    pub exponent_err: f64,
    /// The prefactor (units of y / units of x^exponent).
    pub prefactor: f64,
    /// Points used.
    pub n: usize,
}

/// Fit `y = A x^p` through the points with positive x and y.
pub fn fit_power(points: &[(f64, f64)]) -> Result<PowerFit, AnalyzeError> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .map(|p| (p.0.ln(), p.1.ln()))
        .collect();
    let f = fit_line(&logs)?;
    Ok(PowerFit {
        exponent: f.slope,
        exponent_err: f.slope_err,
        prefactor: f.intercept.exp(),
        n: f.n,
    })
}

/// Mean and sample standard deviation (0 for one value); None for no values.
pub fn mean_std(values: &[f64]) -> Option<(f64, f64)> {
    if values.is_empty() {
        return None;
    }
    let n = values.len() as f64;
    let m = values.iter().sum::<f64>() / n;
    let s = if values.len() > 1 {
        (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    Some((m, s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_outliers() {
        let mut pts: Vec<(f64, f64)> = (0..20).map(|i| (i as f64, 2.0 + 3.0 * i as f64)).collect();
        let f = fit_line(&pts).unwrap();
        assert!((f.slope - 3.0).abs() < 1e-12 && (f.intercept - 2.0).abs() < 1e-12);
        assert!(f.slope_err < 1e-12);
        pts[7].1 += 40.0;
        let (f, kept) = fit_line_clipped(&pts, 2.0).unwrap();
        assert_eq!(kept.len(), 19);
        assert!((f.slope - 3.0).abs() < 1e-12);
        assert!(fit_line(&pts[..1]).is_err());
    }

    #[test]
    fn power_law() {
        let pts: Vec<(f64, f64)> = [1e-3, 1e-2, 0.1, 1.0]
            .iter()
            .map(|&v: &f64| (v, 7.0 * v.powf(0.2)))
            .collect();
        let p = fit_power(&pts).unwrap();
        assert!((p.exponent - 0.2).abs() < 1e-12 && (p.prefactor - 7.0).abs() < 1e-9);
        assert_eq!(mean_std(&[1.0, 3.0]), Some((2.0, 2f64.sqrt())));
    }
}
