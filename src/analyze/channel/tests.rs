use super::*;
use crate::analyze::series::Frame;

const C: f64 = 3.0;

/// A simple-cubic bed (spacing 2R) 0.5 m long, 4 layers deep, 1 wide; a force pulse crosses it
/// at C m/s from y = 0 (leaving at t = 10 ms) and every particle it passed 5 ms earlier is 1 mm
/// higher.
fn synthetic_channel(dir: &std::path::Path) -> String {
    let r = 0.00125;
    std::fs::create_dir_all(dir).unwrap();
    let cols = [
        "id", "type", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "radius",
    ];
    for j in 0..=300 {
        let t = j as f64 * 1e-3;
        let mut rows = Vec::new();
        for iy in 0..200 {
            for iz in 0..4 {
                for ix in 0..1 {
                    let y = (iy as f64 + 0.5) * 2.0 * r;
                    let tp = 0.01 + y / C;
                    let passed = t > tp + 0.005;
                    let z = (iz as f64 + 0.5) * 2.0 * r + if passed { 0.001 } else { 0.0 };
                    let f = 1e-4 + (-((t - tp) / 0.002).powi(2)).exp();
                    let id = (iy * 4 + iz + ix + 1) as f64;
                    let x = (ix as f64 + 0.5) * 2.0 * r;
                    rows.push(vec![id, 1.0, x, y, z, 0.0, 0.1, 0.0, 0.0, f, 0.0, r]);
                }
            }
        }
        let fr = Frame {
            step: j * 100,
            time: 0.0,
            bounds: [[0.0, 0.0025], [0.0, 0.5], [0.0, 0.02]],
            columns: cols.iter().map(|s| s.to_string()).collect(),
            rows,
        };
        std::fs::write(dir.join(format!("shock_{}.dump", j * 100)), fr.to_text()).unwrap();
    }
    format!("{}/shock_*.dump", dir.display())
}

#[test]
fn a_front_at_a_set_speed_and_a_known_rise() {
    let dir = std::env::temp_dir().join(format!("regolith_channel_{}", std::process::id()));
    let s = Series::open(&synthetic_channel(&dir), 1e-5).unwrap();
    let r = analyze(&s, &ChannelOptions::default()).unwrap();
    assert_eq!((r.grid.ny, r.grid.nz), (100, 3));
    assert!((r.scale - 0.25).abs() < 1e-12);
    let cw = r.c_w.as_ref().unwrap();
    assert!((cw.speed - C).abs() < 0.05 * C, "{cw:?}");
    assert!((cw.range.1 - 0.15).abs() < 1e-12 && r.fit_scale == 1.0);
    let cp = r.c_p.as_ref().unwrap();
    assert!((cp.speed - C).abs() < 0.05 * C, "{cp:?}");
    let (dh, spread) = r.dilation_mean.unwrap();
    assert!((dh - 0.001).abs() < 1e-9 && spread < 1e-9, "{dh} {spread}");
    assert!(r.dilation.iter().filter(|d| d.2).count() == 50);
    // behind the front: the c_w range's columns past the piston's cell (0.0075 .. 0.1475 m)
    let (rise, spread) = r.rise.unwrap();
    assert!(
        (rise - 0.001).abs() < 1e-9 && spread < 1e-9,
        "{rise} {spread}"
    );
    assert!(
        (r.packing - std::f64::consts::PI / 6.0).abs() < 1e-9,
        "{}",
        r.packing
    );
    assert_eq!(r.panels.len(), 3);
    assert_eq!(r.panels[0].rows.len(), 800);
    assert!(r.panels[1].rows[0][5].is_nan());
    std::fs::remove_dir_all(&dir).unwrap();
}
