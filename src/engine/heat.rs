//! Heat conduction between touching spheres (`fix heat/gran`, `fix heat/gran/conduction`)
//! and the user per-atom properties it keeps its state in (`fix property/atom`).
//!
//! As LIGGGHTS 3.8.0 does it: the heat fix owns per-atom properties `Temp` (temperature, K),
//! `heatFlux` (W), `heatSource` (W) and `directionalHeatFlux` (W m, three columns), each a
//! property/atom fix of that ID. At the start of each step the fluxes are zeroed; after the
//! forces every listed pair that overlaps exchanges `(T_j - T_i) h` with
//! `h = 4 k_i k_j / (k_i + k_j) sqrt(A)` (A the contact area); at the end of the step
//! `T += (heatFlux + heatSource) dt / (m c)`. Its global value is the thermal energy
//! `sum c m T` (J) of all particles.

use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle, PerAtomShape};
use crate::engine::neighbor::Pair;
use crate::engine::particles::Particles;

/// Name (fix ID) of the per-atom temperature (K).
pub const TEMP: &str = "Temp";
/// Name of the per-atom conductive heat flow into each particle (W).
pub const HEAT_FLUX: &str = "heatFlux";
/// Name of the per-atom heat source (W).
pub const HEAT_SOURCE: &str = "heatSource";
/// Name of the per-atom directional heat flux (three columns, W m).
pub const DIRECTIONAL: &str = "directionalHeatFlux";

/// `fix ID GROUP property/atom NAME scalar|vector RESTART COMM_GHOST COMM_REV VALUES...`:
/// a per-atom property, its values held in the particle array named by the fix ID.
#[derive(Debug, Clone, PartialEq)]
pub struct PropertyAtom {
    /// The fix ID, which names the particle array holding the values.
    pub id: String,
    /// The variable name (`set ... property/atom NAME` and other fixes find it by it).
    pub name: String,
    /// The default values, one per column (one for a scalar); new particles start with them.
    pub defaults: Vec<f64>,
    /// `vector` style (a per-atom array), else a per-atom scalar.
    pub vector: bool,
    /// Restart flag `yes`: the values travel through restart files.
    pub restart: bool,
    /// Defined and not yet through a run's setup (LIGGGHTS refuses `set` on it then).
    pub fresh: bool,
}

/// How the conduction contact area is taken (`contact_area` keyword).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactArea {
    /// The intersection circle of the two spheres (default).
    Overlap,
    /// A fixed area (length^2).
    Constant(f64),
    /// The cross-section of the larger sphere.
    Projection,
}

/// `fix ID GROUP heat/gran[/conduction] initial_temperature T0 [contact_area ...]`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatGran {
    /// The style name as written (`heat/gran` or `heat/gran/conduction`).
    pub style: String,
    /// The initial temperature (K) as LIGGGHTS passes it on (rounded through `%f`, `%e`).
    pub t0: f64,
    /// The contact-area model.
    pub area: ContactArea,
    /// Thermal conductivity per type (W/(m K), index type - 1), read at each run's start.
    pub conductivity: Vec<f64>,
    /// Thermal capacity per type (J/(kg K), index type - 1), read at each run's start.
    pub capacity: Vec<f64>,
    /// IDs of the property/atom fixes (and particle arrays) holding `Temp`, `heatFlux`,
    /// `heatSource` and `directionalHeatFlux`.
    pub arrays: [String; 4],
    /// `area_correction yes`: overlaps scaled per type pair by
    /// `(Y_eff / Y_eff,original)^(1/stress-strain exponent)` before the area is taken.
    pub area_correction: bool,
    /// Those factors (row-major over type pairs), set at each run's start.
    pub overlap_ratio: Vec<f64>,
    /// `store_contact_data yes`: the arrays of `contactAreaConduction` (mean conduction
    /// area per contact, length^2), `nContactsConduction`, `wallHeattransferCoeff` and
    /// `wallTemp` (zero: no wall heat transfer).
    pub contact_data: Option<[String; 4]>,
}

/// LIGGGHTS's floor below which a conductivity conducts nothing (W/(m K)).
const SMALL_CONDUCTIVITY: f64 = 1e-6;
/// LIGGGHTS's floor below which a capacity leaves the temperature unchanged (J/(kg K)).
const SMALL_CAPACITY: f64 = 1e-8;

/// `T0` as LIGGGHTS hands it on: written with `%f` to the transport equation, which writes
/// it with `%e` as the default of `Temp`.
pub fn initial_temperature(t0: f64) -> f64 {
    let fixed: f64 = format!("{t0:.6}").parse().unwrap_or(t0);
    format!("{fixed:.6e}").parse().unwrap_or(fixed)
}

/// Index of the per-atom array `name` of `width` columns, if the particles hold it.
fn array(p: &Particles, name: &str, width: usize) -> Option<usize> {
    p.extra
        .iter()
        .position(|e| e.name == name && e.width == width)
}

/// Add (or reset) the per-atom array of a property/atom fix `id`: every particle takes
/// the defaults, and particles added later start with them.
pub fn add_property(p: &mut Particles, id: &str, defaults: &[f64]) {
    let k = p.extra_index(id, defaults.len());
    let e = &mut p.extra[k];
    for row in e.data.chunks_mut(defaults.len()) {
        row.copy_from_slice(defaults);
    }
    e.fill = defaults.to_vec();
}

impl HeatGran {
    /// Start of a step: heat flows (W) and directional flows (W m) back to zero.
    pub fn zero_flows(&self, p: &mut Particles) {
        if let Some(k) = array(p, &self.arrays[1], 1) {
            p.extra[k].data.fill(0.0);
        }
        if let Some(k) = array(p, &self.arrays[3], 3) {
            p.extra[k].data.fill(0.0);
        }
    }

    /// Conduction through every listed pair that overlaps, in list order (`group`: the
    /// fix's group bit; a pair counts when either particle is in it).
    pub fn conduct(&self, p: &mut Particles, pairs: &[Pair], group: u32) {
        let (Some(kt), Some(kf), Some(kd)) = (
            array(p, &self.arrays[0], 1),
            array(p, &self.arrays[1], 1),
            array(p, &self.arrays[3], 3),
        ) else {
            return;
        };
        let mut flux_arr = std::mem::take(&mut p.extra[kf].data);
        let mut dir = std::mem::take(&mut p.extra[kd].data);
        // per-particle contact data: (area sum, contact count), zeroed each step
        let stored = self.contact_data.as_ref().and_then(|ids| {
            let ks: Vec<usize> = ids.iter().filter_map(|id| array(p, id, 1)).collect();
            (ks.len() == 4).then_some(ks)
        });
        let (mut area_sum, mut contacts) = match &stored {
            Some(ks) => {
                for &k in &ks[2..] {
                    p.extra[k].data.fill(0.0);
                }
                (vec![0.0; p.len()], vec![0.0; p.len()])
            }
            None => (Vec::new(), Vec::new()),
        };
        let ntypes = (self.overlap_ratio.len() as f64).sqrt() as usize;
        let temp = &p.extra[kt].data;
        for pair in pairs {
            let (i, j) = (pair.i as usize, pair.j as usize);
            if p.mask[i] & group == 0 && p.mask[j] & group == 0 {
                continue;
            }
            let (xi, xj) = (p.x[i], p.x[j]);
            let del = [
                xi[0] - (xj[0] + pair.shift[0]),
                xi[1] - (xj[1] + pair.shift[1]),
                xi[2] - (xj[2] + pair.shift[2]),
            ];
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            let (ri, rj) = (p.radius[i], p.radius[j]);
            let radsum = ri + rj;
            if rsq >= radsum * radsum {
                continue;
            }
            let mut r = rsq.sqrt();
            if self.area_correction && ntypes > 0 {
                let (ti, tj) = (p.kind[i] as usize - 1, p.kind[j] as usize - 1);
                let delta_n = (radsum - r) * self.overlap_ratio[ti * ntypes + tj];
                r = radsum - delta_n;
            }
            let area = match self.area {
                ContactArea::Overlap => {
                    if r < ri.max(rj) {
                        let small = ri.min(rj);
                        small * small * std::f64::consts::PI
                    } else {
                        -std::f64::consts::PI / 4.0
                            * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
                            / (r * r)
                    }
                }
                ContactArea::Constant(a) => a,
                ContactArea::Projection => {
                    let big = ri.max(rj);
                    std::f64::consts::PI * big * big
                }
            };
            let ki = self.conductivity[p.kind[i] as usize - 1];
            let kj = self.conductivity[p.kind[j] as usize - 1];
            let hc = if ki < SMALL_CONDUCTIVITY || kj < SMALL_CONDUCTIVITY {
                0.0
            } else {
                4.0 * ki * kj / (ki + kj) * area.sqrt()
            };
            let flux = (temp[j] - temp[i]) * hc;
            let d = [flux * del[0], flux * del[1], flux * del[2]];
            flux_arr[i] += flux;
            for c in 0..3 {
                dir[3 * i + c] += 0.50 * d[c];
            }
            flux_arr[j] -= flux;
            for c in 0..3 {
                dir[3 * j + c] += 0.50 * d[c];
            }
            if stored.is_some() {
                area_sum[i] += area;
                contacts[i] += 1.0;
                area_sum[j] += area;
                contacts[j] += 1.0;
            }
        }
        p.extra[kf].data = flux_arr;
        p.extra[kd].data = dir;
        if let Some(ks) = stored {
            for (a, &n) in area_sum.iter_mut().zip(&contacts) {
                if n > 0.5 {
                    *a /= n;
                }
            }
            p.extra[ks[0]].data = area_sum;
            p.extra[ks[1]].data = contacts;
        }
    }

    /// End of a step: the temperatures (K) of the group's particles advance by
    /// `(heatFlux + heatSource) dt / (m c)` (dt in s).
    pub fn advance_temperatures(&self, p: &mut Particles, group: u32, dt: f64) {
        let (Some(kt), Some(kf), Some(ks)) = (
            array(p, &self.arrays[0], 1),
            array(p, &self.arrays[1], 1),
            array(p, &self.arrays[2], 1),
        ) else {
            return;
        };
        let mut temp = std::mem::take(&mut p.extra[kt].data);
        let (flux, source) = (&p.extra[kf].data, &p.extra[ks].data);
        for (i, t) in temp.iter_mut().enumerate() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let c = self.capacity[p.kind[i] as usize - 1];
            if c.abs() > SMALL_CAPACITY {
                *t += (flux[i] + source[i] * 1.0) * dt / (p.mass[i] * c);
            }
        }
        p.extra[kt].data = temp;
    }
}

/// What a mesh wall needs to conduct heat into the particles touching a mesh kept at a
/// fixed temperature (`fix mesh/surface ... temperature T`).
#[derive(Debug, Clone, PartialEq)]
pub struct WallHeat<'a> {
    /// Index of the per-atom temperature array (K).
    temp: usize,
    /// Index of the per-atom heat flow array (W).
    flux: usize,
    /// Thermal conductivity per type (W/(m K), index type - 1).
    conductivity: &'a [f64],
    /// The heat fix's `area_correction` overlap factors (row-major over type pairs; empty
    /// without it).
    overlap_ratio: &'a [f64],
}

impl<'a> WallHeat<'a> {
    /// The wall conduction of the heat fix `h` (None when the particles lack its arrays).
    pub fn new(h: &'a HeatGran, p: &Particles) -> Option<Self> {
        Some(Self {
            temp: array(p, &h.arrays[0], 1)?,
            flux: array(p, &h.arrays[1], 1)?,
            conductivity: &h.conductivity,
            overlap_ratio: &h.overlap_ratio,
        })
    }

    /// One particle-wall contact, as LIGGGHTS's wall/gran adds it: particle `i` of radius
    /// `radius` (m) overlapping by `overlap` (m) a wall of atom type `wall_type` at `t_wall`
    /// (K) gains `(t_wall - T_i) h` (W), `h = 4 k_i k_w / (k_i + k_w) sqrt(A)`, A the
    /// circle where the sphere cuts the wall, `pi (r^2 - (r - overlap)^2)` (m^2).
    #[inline]
    pub fn add(
        &self,
        p: &mut Particles,
        i: usize,
        radius: f64,
        overlap: f64,
        wall_type: usize,
        t_wall: f64,
    ) {
        let it = p.kind[i] as usize;
        let ntypes = self.conductivity.len();
        let mut delta_n = overlap;
        if !self.overlap_ratio.is_empty() && wall_type <= ntypes {
            delta_n *= self.overlap_ratio[(it - 1) * ntypes + wall_type - 1];
        }
        let r = radius - delta_n;
        let area = (radius * radius - r * r) * std::f64::consts::PI * 1.0;
        let kp = self.conductivity.get(it - 1).copied().unwrap_or(0.0);
        let kw = self
            .conductivity
            .get(wall_type.wrapping_sub(1))
            .copied()
            .unwrap_or(0.0);
        let hc = if kp.abs() < SMALL_CONDUCTIVITY || kw.abs() < SMALL_CONDUCTIVITY {
            0.0
        } else {
            4.0 * kp * kw / (kp + kw) * area.sqrt()
        };
        let flow = (t_wall - p.extra[self.temp].data[i]) * hc;
        p.extra[self.flux].data[i] += flow;
    }
}

impl FixStyle for HeatGran {
    fn name(&self) -> &str {
        &self.style
    }

    fn initial_integrate(&mut self, p: &mut Particles, _at: &FixStep) {
        self.zero_flows(p);
    }

    fn final_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        self.advance_temperatures(p, at.group, at.dt);
    }

    /// The temperature (K), one per particle.
    fn per_atom_shape(&self) -> PerAtomShape {
        PerAtomShape::Vector
    }

    fn per_atom(&self, p: &Particles) -> Vec<f64> {
        property_values(p, &self.arrays[0], 1)
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}

impl FixStyle for PropertyAtom {
    fn name(&self) -> &str {
        "property/atom"
    }

    /// A per-atom vector for a scalar property, an array of its columns for a vector one.
    fn per_atom_shape(&self) -> PerAtomShape {
        if self.vector {
            PerAtomShape::Array(self.defaults.len())
        } else {
            PerAtomShape::Vector
        }
    }

    fn per_atom(&self, p: &Particles) -> Vec<f64> {
        property_values(p, &self.id, self.defaults.len())
    }

    /// Its values are in the particle arrays, which copies take over.
    fn keeps_per_atom_state(&self) -> bool {
        false
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}

/// The thermal energy `sum c m T` (J) of all particles, summed in particle order
/// (`capacity` per type, J/(kg K); `temp`: the temperature array's ID); 0 without it.
pub fn thermal_energy(p: &Particles, temp: &str, capacity: &[f64]) -> f64 {
    let Some(kt) = array(p, temp, 1) else {
        return 0.0;
    };
    let temp = &p.extra[kt].data;
    let mut sum = 0.0;
    for ((&kind, &mass), &t) in p.kind.iter().zip(&p.mass).zip(temp) {
        let c = capacity.get(kind as usize - 1).copied().unwrap_or(0.0);
        sum += c * mass * t;
    }
    sum
}

/// The per-atom values of the property/atom array `id` (particle-major, `width` columns),
/// zeros if the particles do not hold it.
pub fn property_values(p: &Particles, id: &str, width: usize) -> Vec<f64> {
    match array(p, id, width) {
        Some(k) => p.extra[k].data.clone(),
        None => vec![0.0; width * p.len()],
    }
}

impl crate::engine::sim::Simulation {
    /// At each run's start (LIGGGHTS's `init`): the heat fixes read the conductivities and
    /// capacities per type, and new property/atom fixes are no longer fresh.
    /// A mesh wall touching a mesh held at a temperature needs the particles' temperatures:
    /// without a heat fix LIGGGHTS stops at the run's init.
    fn check_wall_temperatures(&self) -> Result<(), EngineError> {
        let heated = |id: &String| {
            self.fixes
                .iter()
                .any(|f| &f.id == id && f.kind.mesh().is_some_and(|m| m.temperature.is_some()))
        };
        let wall_needs = self
            .fixes
            .iter()
            .filter_map(|f| f.kind.mesh_wall())
            .any(|w| w.meshes.iter().any(heated));
        let has_heat = self
            .fixes
            .iter()
            .any(|f| f.kind.style_as::<HeatGran>().is_some());
        if wall_needs && !has_heat {
            return Err("Could not locate a fix/property storing value(s) for Temp as requested by wall/gran."
                .into());
        }
        Ok(())
    }

    pub(crate) fn init_heat(&mut self) -> Result<(), EngineError> {
        self.check_wall_temperatures()?;
        let ntypes = self.ntypes as usize;
        let mut heat_styles: Vec<&str> = Vec::new();
        let mut resolved = Vec::new();
        for (k, f) in self.fixes.iter().enumerate() {
            let Some(h) = f.kind.style_as::<HeatGran>() else {
                continue;
            };
            if heat_styles.contains(&f.style.as_str()) {
                return Err(format!(
                    "Fix {} (id {}): cannot have more than one fix of this style",
                    f.style, f.id
                )
                .into());
            }
            heat_styles.push(&f.style);
            if self.pair.is_none() && self.pair_selection.is_none() {
                return Err(format!(
                    "Fix {} (id {}): needs a granular pair style to be used",
                    f.style, f.id
                )
                .into());
            }
            let per_type = |name: &str| -> Result<Vec<f64>, EngineError> {
                let missing = || {
                    format!(
                        "Could not locate a fix/property storing value(s) for {name} as requested by {}.",
                        f.style
                    )
                };
                let (style, _, values) = self.property(name).ok_or_else(missing)?;
                if style != "peratomtype" || values.len() < ntypes {
                    return Err(missing().into());
                }
                Ok(values[..ntypes].to_vec())
            };
            let conductivity = per_type("thermalConductivity")?;
            if conductivity.iter().any(|&k| k < 0.0) {
                return Err(
                    format!("Fix {}: Thermal conductivity must not be < 0", f.style).into(),
                );
            }
            let capacity = per_type("thermalCapacity")?;
            let ratio = if h.area_correction {
                self.overlap_ratios(&f.style, &per_type)?
            } else {
                Vec::new()
            };
            resolved.push((k, conductivity, capacity, ratio));
        }
        for (k, conductivity, capacity, ratio) in resolved {
            if let Some(h) = self.fixes[k].kind.style_as_mut::<HeatGran>() {
                h.conductivity = conductivity;
                h.capacity = capacity;
                h.overlap_ratio = ratio;
            }
        }
        for f in &mut self.fixes {
            if let Some(pa) = f.kind.property_atom_mut() {
                pa.fresh = false;
            }
        }
        Ok(())
    }

    /// `area_correction`: per type pair `(Y_eff / Y_eff,original)^(1/e)`, e the normal
    /// model's stress-strain exponent (Hertz 3/2, Hooke 1), from `youngsModulus`,
    /// `poissonsRatio` and `youngsModulusOriginal` (read by `per_type`).
    fn overlap_ratios(
        &self,
        style: &str,
        per_type: &dyn Fn(&str) -> Result<Vec<f64>, EngineError>,
    ) -> Result<Vec<f64>, EngineError> {
        let normal = self
            .pair_selection
            .as_ref()
            .map(|s| s.normal.as_str())
            .unwrap_or("");
        let exponent = if normal.starts_with("hertz") {
            1.5
        } else if normal.starts_with("hooke") {
            1.0
        } else {
            return Err(format!(
                "Fix {style}: area_correction with normal model {normal}: not supported yet"
            )
            .into());
        };
        let expo = 1.0 / exponent;
        let y = per_type("youngsModulus")?;
        let nu = per_type("poissonsRatio")?;
        let y0 = per_type("youngsModulusOriginal")?;
        let n = y.len();
        let mut out = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let yeff = 1. / ((1. - nu[i].powf(2.)) / y[i] + (1. - nu[j].powf(2.)) / y[j]);
                let yorig = 1. / ((1. - nu[i].powf(2.)) / y0[i] + (1. - nu[j].powf(2.)) / y0[j]);
                out[i * n + j] = (yeff / yorig).powf(expo);
            }
        }
        Ok(out)
    }

    /// After the forces: conduction of every heat fix through the pair list.
    pub(crate) fn conduct_heat(&mut self) {
        for f in &self.fixes {
            if let Some(h) = f.kind.style_as::<HeatGran>() {
                h.conduct(&mut self.particles, &self.list.pairs, f.group);
            }
        }
    }

    /// The global values of the heat fixes: `f_ID` of a heat fix is the thermal energy (J);
    /// a property/atom fix has no global value LIGGGHTS's thermo reads (its error). None for
    /// other fixes.
    pub(crate) fn heat_value(
        &self,
        id: &str,
        index: Option<usize>,
    ) -> Option<Result<f64, EngineError>> {
        let f = self.fixes.iter().find(|f| f.id == id)?;
        if f.kind.property_atom().is_some() {
            return Some(Err(match index {
                None => "Thermo fix does not compute scalar".into(),
                Some(_) => "Thermo fix does not compute vector".into(),
            }));
        }
        match (f.kind.style_as::<HeatGran>()?, index) {
            (h, None) => {
                let capacity = if h.capacity.is_empty() {
                    self.property("thermalCapacity")
                        .map(|(_, _, v)| v)
                        .unwrap_or_default()
                } else {
                    h.capacity.clone()
                };
                Some(Ok(thermal_energy(&self.particles, &h.arrays[0], &capacity)))
            }
            (_, Some(_)) => Some(Err("Thermo fix does not compute vector".into())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initial_temperature_rounds_as_liggghts_prints_it() {
        assert_eq!(initial_temperature(300.0), 300.0);
        assert_eq!(initial_temperature(1234.56789), 1234.568);
        assert_eq!(initial_temperature(0.0000004), 0.0);
    }

    #[test]
    fn two_touching_spheres_exchange_heat_and_keep_energy() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.5, 1000.0);
        p.push(2, 1, [0.9, 0.0, 0.0], 0.5, 1000.0);
        for (name, d) in [
            (TEMP, vec![300.0]),
            (HEAT_FLUX, vec![0.0]),
            (HEAT_SOURCE, vec![0.0]),
            (DIRECTIONAL, vec![0.0; 3]),
        ] {
            add_property(&mut p, name, &d);
        }
        let k = array(&p, TEMP, 1).unwrap();
        p.extra[k].data[1] = 400.0;
        let h = HeatGran {
            style: "heat/gran".into(),
            t0: 300.0,
            area: ContactArea::Overlap,
            conductivity: vec![2.0],
            capacity: vec![10.0],
            arrays: [TEMP, HEAT_FLUX, HEAT_SOURCE, DIRECTIONAL].map(String::from),
            area_correction: false,
            overlap_ratio: Vec::new(),
            contact_data: None,
        };
        let before = thermal_energy(&p, TEMP, &h.capacity);
        let pairs = [Pair {
            i: 0,
            j: 1,
            shift: [0.0; 3],
        }];
        h.zero_flows(&mut p);
        h.conduct(&mut p, &pairs, 1);
        let kf = array(&p, HEAT_FLUX, 1).unwrap();
        // contact radius^2 = 0.25 - 0.45^2 = 0.0475; h = 4 * 1 * sqrt(pi 0.0475)
        let hc = 4.0 * (std::f64::consts::PI * 0.0475f64).sqrt();
        assert!((p.extra[kf].data[0] - 100.0 * hc).abs() < 1e-9);
        assert_eq!(p.extra[kf].data[1], -p.extra[kf].data[0]);
        h.advance_temperatures(&mut p, 1, 1e-3);
        assert!((thermal_energy(&p, TEMP, &h.capacity) - before).abs() < 1e-9 * before);
        assert!(p.extra[k].data[0] > 300.0 && p.extra[k].data[1] < 400.0);
    }
}
