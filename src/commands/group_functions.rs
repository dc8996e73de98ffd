//! Group functions of formulas about the centre of mass: `gyration(g)`, `angmom(g,dim)`,
//! `torque(g,dim)`, `inertia(g,xx|yy|zz|xy|yz|xz)` and `omega(g,dim)`, each with an optional
//! region, summed over the members in particle order as LIGGGHTS 3.8.0's Group does.

use crate::engine::error::EngineError;
use crate::engine::sim::Simulation;

/// The value of group function `name` over `members` (particle indices) of total `mass`;
/// `args[1]` is the component for all but `gyration`.
pub fn about_centre(
    sim: &Simulation,
    name: &str,
    args: &[String],
    members: &[usize],
    mass: f64,
) -> Result<f64, EngineError> {
    let invalid = || EngineError::from("Invalid group function in variable formula");
    let p = &sim.particles;
    let unwrap = |i: usize| -> [f64; 3] {
        [0, 1, 2].map(|d| p.x[i][d] + p.image[i][d] as f64 * sim.domain.length(d))
    };
    let mut cm = [0.0; 3];
    for &i in members {
        let u = unwrap(i);
        for d in 0..3 {
            cm[d] += u[d] * p.mass[i];
        }
    }
    if mass > 0.0 {
        cm = cm.map(|c| c / mass);
    }
    let arm = |i: usize| {
        let u = unwrap(i);
        [u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]]
    };
    let angmom = || {
        let mut l = [0.0; 3];
        for &i in members {
            let ([dx, dy, dz], m, v) = (arm(i), p.mass[i], p.v[i]);
            l[0] += m * (dy * v[2] - dz * v[1]);
            l[1] += m * (dz * v[0] - dx * v[2]);
            l[2] += m * (dx * v[1] - dy * v[0]);
        }
        l
    };
    let inertia = || {
        let mut t = [[0.0; 3]; 3];
        for &i in members {
            crate::engine::momentum::add_inertia(&mut t, arm(i), p.mass[i]);
        }
        crate::engine::momentum::mirror_inertia(&mut t);
        t
    };
    let dim = || match args.get(1).map(String::as_str) {
        Some("x") => Ok(0),
        Some("y") => Ok(1),
        Some("z") => Ok(2),
        _ => Err(invalid()),
    };
    Ok(match name {
        "gyration" => {
            let mut rg = 0.0;
            for &i in members {
                let [dx, dy, dz] = arm(i);
                rg += (dx * dx + dy * dy + dz * dz) * p.mass[i];
            }
            if mass > 0.0 {
                (rg / mass).sqrt()
            } else {
                0.0
            }
        }
        "angmom" => angmom()[dim()?],
        "torque" => {
            let mut tq = [0.0; 3];
            for &i in members {
                let ([dx, dy, dz], f) = (arm(i), p.f[i]);
                tq[0] += dy * f[2] - dz * f[1];
                tq[1] += dz * f[0] - dx * f[2];
                tq[2] += dx * f[1] - dy * f[0];
            }
            tq[dim()?]
        }
        "inertia" => {
            let (r, c) = match args.get(1).map(String::as_str) {
                Some("xx") => (0, 0),
                Some("yy") => (1, 1),
                Some("zz") => (2, 2),
                Some("xy") => (0, 1),
                Some("yz") => (1, 2),
                Some("xz") => (0, 2),
                _ => return Err(invalid()),
            };
            inertia()[r][c]
        }
        "omega" => {
            let d = dim()?;
            crate::engine::momentum::omega(angmom(), inertia())[d]
        }
        other => {
            return Err(EngineError::Unsupported(format!(
                "group function {other}()"
            )))
        }
    })
}
