use super::*;
use crate::analyze::series::Frame;

const A: f64 = 50e-6; // particle radius (m)
const R0: f64 = 0.002; // inner radius (m)

/// Ten rows of spheres around a cavity whose edge is R0 (1 + corr cos 6 theta); particles
/// inside radius R0 + speed t move outward at 1 m/s; |f| = 1 + 0.5 cos 12 theta.
fn ring_frame(step: i64, t: f64, corr: f64, speed: f64) -> Frame {
    let d = 2.0 * A;
    let mut rows = Vec::new();
    for j in 0..10 {
        let n = (2.0 * PI * (R0 + A + j as f64 * d) / d) as usize;
        for k in 0..n {
            let th = 2.0 * PI * (k as f64 + 0.5 * (j % 2) as f64) / n as f64;
            let r = R0 * (1.0 + corr * (6.0 * th).cos()) + A + j as f64 * d;
            let v = if speed > 0.0 && r < R0 + speed * t {
                1.0
            } else {
                0.0
            };
            let f = 1.0 + 0.5 * (12.0 * th).cos();
            let (c, s) = (th.cos(), th.sin());
            let id = (rows.len() + 1) as f64;
            rows.push(vec![
                id,
                1.0,
                r * c,
                r * s,
                A,
                v * c,
                v * s,
                0.0,
                f * c,
                f * s,
                0.0,
                A,
            ]);
        }
    }
    let cols = [
        "id", "type", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "radius",
    ];
    Frame {
        step,
        time: t,
        bounds: [[-0.01, 0.01], [-0.01, 0.01], [0.0, 0.001]],
        columns: cols.iter().map(|s| s.to_string()).collect(),
        rows,
    }
}

fn write_series(dir: &std::path::Path, corr: f64, speed: f64) -> String {
    std::fs::create_dir_all(dir).unwrap();
    for j in 0..=10 {
        let fr = ring_frame(j * 1000, j as f64 * 1e-3, corr, speed);
        std::fs::write(dir.join(format!("ring_{}.dump", j * 1000)), fr.to_text()).unwrap();
    }
    format!("{}/ring_*.dump", dir.display())
}

#[test]
fn a_known_corrugation() {
    let dir = std::env::temp_dir().join(format!("regolith_ring_c_{}", std::process::id()));
    let s = Series::open(&write_series(&dir, 0.05, 0.0), 1e-6).unwrap();
    let r = analyze(&s, &RingOptions::default()).unwrap();
    let st = r.states.last().unwrap();
    assert!((st.amplitude - 0.05).abs() < 0.005, "{st:?}");
    assert!((st.r_in - 0.95 * R0).abs() < 0.01 * R0 && (st.r_out - 1.05 * R0).abs() < 0.01 * R0);
    assert!((st.rms - 0.05 / 2f64.sqrt()).abs() < 0.005, "{}", st.rms);
    assert!(st.front.is_nan());
    assert_eq!(r.surface.len(), 72);
    assert!((r.diameter - 2.0 * A).abs() < 1e-15);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_front_moving_at_a_set_speed_and_force_chain_spacing() {
    let dir = std::env::temp_dir().join(format!("regolith_ring_f_{}", std::process::id()));
    let speed = 0.08; // m/s: 0.8 mm (8 diameters) in 10 ms
    let s = Series::open(&write_series(&dir, 0.0, speed), 1e-6).unwrap();
    let r = analyze(&s, &RingOptions::default()).unwrap();
    let pts: Vec<(f64, f64)> = r
        .states
        .iter()
        .filter(|s| s.front.is_finite())
        .map(|s| (s.t, s.front))
        .collect();
    assert!(pts.len() >= 9, "{pts:?}");
    let fit = crate::analyze::fit::fit_line(&pts).unwrap();
    assert!((fit.slope - speed).abs() < 0.1 * speed, "{fit:?}");
    assert!(r.states[0].amplitude < 0.03);
    // the force field's mode 12 in every band (no corrugation to modulate the density)
    assert_eq!(r.bands.len(), 3);
    for b in &r.bands {
        assert_eq!(b.mode, 12, "{:?}", b.radii);
        let mid = 0.5 * (b.radii.0 + b.radii.1);
        assert!((b.spacing_diameters - 2.0 * PI * mid / 12.0 / (2.0 * A)).abs() < 1e-9);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn spectrum_of_a_pure_mode() {
    let sig: Vec<f64> = (0..64)
        .map(|k| 2.0 + (2.0 * PI * 5.0 * k as f64 / 64.0).sin())
        .collect();
    let p = azimuthal_power(&sig);
    assert_eq!(p.len(), 32);
    assert!((p[4] - 32.0f64.powi(2)).abs() < 1e-9);
    assert!(p.iter().enumerate().all(|(k, v)| k == 4 || *v < 1e-18));
}
