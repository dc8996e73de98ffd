use super::*;
use crate::analyze::series::Frame;

/// A synthetic struck column: `n` layers (spacing d) below a striker (type 2), a Gaussian
/// force pulse reaching layer k at t_k = t0 + k d / c, written as a `*` series.
pub(crate) fn synthetic_chain(dir: &std::path::Path, c: f64, n: usize) -> String {
    let d = 0.02;
    std::fs::create_dir_all(dir).unwrap();
    let cols = ["id", "type", "x", "y", "z", "fx", "fy", "fz"];
    for j in 0..=150 {
        let t = j as f64 * 1e-3;
        let mut rows = Vec::new();
        for k in 0..n {
            let tk = 0.001 + k as f64 * d / c;
            let f = 2.0 * (-((t - tk) / 0.004).powi(2)).exp();
            let z = (n - 1 - k) as f64 * d;
            rows.push(vec![(k + 1) as f64, 1.0, 0.0, 0.0, z, 0.0, 0.1 * f, f]);
            // a side particle of the same layer, weaker
            rows.push(vec![(k + 1 + n) as f64, 1.0, d, 0.0, z, 0.0, 0.0, 0.3 * f]);
        }
        rows.push(vec![
            (2 * n + 1) as f64,
            2.0,
            0.0,
            0.0,
            n as f64 * d,
            0.0,
            0.0,
            0.5,
        ]);
        let fr = Frame {
            step: j * 1000,
            time: 0.0,
            bounds: [[-0.1, 0.1], [-0.1, 0.1], [-0.1, 1.0]],
            columns: cols.iter().map(|s| s.to_string()).collect(),
            rows,
        };
        std::fs::write(dir.join(format!("chain_{}.dump", j * 1000)), fr.to_text()).unwrap();
    }
    format!("{}/chain_*.dump", dir.display())
}

#[test]
fn a_front_at_a_set_speed_is_measured() {
    let dir = std::env::temp_dir().join(format!("regolith_chain_{}", std::process::id()));
    let pattern = synthetic_chain(&dir, 5.0, 30);
    let s = Series::open(&pattern, 1e-6).unwrap();
    let r = analyze(&s, &ChainOptions::default()).unwrap();
    assert!((r.fit.slope - 5.0).abs() < 0.05, "{:?}", r.fit);
    assert!(r.fit.slope_err < 0.05);
    assert_eq!(r.layers.len(), 30);
    assert!(!r.layers[0].fitted && !r.layers[29].fitted && r.layers[5].fitted);
    assert!((r.layers[3].distance - 0.06).abs() < 1e-12);
    assert_eq!(r.particles.len(), 60);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_sweep_recovers_the_exponent_and_flags_strong_impacts() {
    let fit = |c: f64| LineFit {
        slope: c,
        slope_err: 0.01,
        intercept: 0.0,
        n: 10,
        rms: 0.0,
    };
    let mut runs = vec![(1e-6, fit(0.9)), (1e-5, fit(1.1))];
    for v in [1e-3, 1e-2, 0.1, 1.0] {
        runs.push((v, fit(8.0 * f64::powf(v, 0.2))));
    }
    runs.push((1.0, fit(8.0)));
    let s = sweep(&runs, 1e-4, &Material::SOFT);
    let p = s.power.unwrap();
    assert!((p.exponent - 0.2).abs() < 1e-9, "{p:?}");
    let (c0, spread) = s.sound_speed.unwrap();
    assert!((c0 - 1.0).abs() < 1e-12 && spread > 0.1);
    assert_eq!(s.points.len(), 6);
    assert_eq!(s.points[5].runs, 2);
    assert!(s.points[4].above_limit && !s.points[2].above_limit);
    assert!((Material::SOFT.elastic_limit() - 0.0094).abs() < 1e-4);
    assert!((Material::STEEL.elastic_limit() - 1.2).abs() < 0.05);
}
