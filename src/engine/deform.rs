//! `fix deform` on an orthogonal box: every N steps, at the end of the step, the box's x, y
//! and z bounds move to the values their styles give for the current step, atoms of the
//! group are carried along (`remap x`, through the box's fractional coordinates), and the
//! rate the box edges move at is kept for `remap v`, which adds it to the velocity of an
//! atom that crosses a periodic face when the atoms are wrapped at a list build. As
//! LIGGGHTS 3.8.0 does: a run starts the ramps from the box it starts with (or, with `run
//! ... start`, from the box when the fix was defined) and they end at the run's last step.

use crate::engine::error::EngineError;

/// How one box dimension changes (lengths in box units, rates per time unit).
#[derive(Debug, Clone, PartialEq)]
pub enum Style {
    /// Not changed by the fix.
    None,
    /// `final lo hi`: the bounds at the end of the run (length).
    Final(f64, f64),
    /// `delta dlo dhi`: the bounds' changes over the run (length).
    Delta(f64, f64),
    /// `scale factor`: the length at the end of the run over the length at its start.
    Scale(f64),
    /// `vel V`: the length changes at this speed (length/time).
    Vel(f64),
    /// `erate R`: engineering strain rate (1/time).
    Erate(f64),
    /// `trate R`: true strain rate (1/time).
    Trate(f64),
    /// `volume`: the length that keeps the box volume.
    Volume,
    /// `wiggle A Tp`: the length oscillates by amplitude A (length) with period Tp (time).
    Wiggle(f64, f64),
    /// `variable v_d v_r`: equal-style variables of the length change (length) and its
    /// rate (length/time).
    Variable(String, String),
}

/// Which dimensions a `volume` dimension follows (LIGGGHTS's ONE_FROM_ONE, ONE_FROM_TWO,
/// TWO_FROM_ONE), as indices of the other dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Link {
    /// The volume's length from one changing dimension, the other kept fixed.
    OneFromOne { fixed: usize, dynamic: usize },
    /// The volume's length from two changing dimensions.
    OneFromTwo(usize, usize),
    /// Two `volume` dimensions share what one changing dimension leaves (`fixed` is the
    /// other volume dimension).
    TwoFromOne { fixed: usize, dynamic: usize },
}

/// `remap x|v|none`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Remap {
    /// Atoms of the group move with the box.
    X,
    /// Atoms of the group crossing a periodic face take the box edges' velocity difference.
    V,
    /// Neither.
    None,
}

/// One dimension's ramp: its style, and bounds (length) at the fix's definition, at the run's
/// start and end, and those the current step asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct Dim {
    /// How the dimension changes.
    pub style: Style,
    /// For `volume`: the dimensions it follows (set at definition).
    pub link: Option<Link>,
    /// Bounds when the fix was defined.
    pub initial: (f64, f64),
    /// Box volume when the fix was defined (volume).
    pub vol_initial: f64,
    /// Bounds at the ramp's start.
    pub start: (f64, f64),
    /// Box volume at the ramp's start (volume).
    pub vol_start: f64,
    /// Bounds at the ramp's end.
    pub stop: (f64, f64),
    /// Bounds asked for at the current step.
    pub target: (f64, f64),
}

/// `fix deform N x|y|z STYLE ... [remap x|v|none] [flip yes|no] [units box|lattice]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Deform {
    /// Change the box every this many steps.
    pub every: i64,
    /// x, y, z.
    pub dims: [Dim; 3],
    /// What happens to the atoms.
    pub remap: Remap,
    /// Rate of change of each box length (length/time; LIGGGHTS's `h_rate`).
    pub h_rate: [f64; 3],
    /// Rate of change of each lower bound (length/time; `h_ratelo`).
    pub h_ratelo: [f64; 3],
}

/// The box's current bounds and lengths, as the fix reads them.
#[derive(Debug, Clone, Copy)]
pub struct BoxNow {
    /// Lower bounds (length).
    pub lo: [f64; 3],
    /// Upper bounds (length).
    pub hi: [f64; 3],
}

impl BoxNow {
    fn volume(&self) -> f64 {
        (self.hi[0] - self.lo[0]) * (self.hi[1] - self.lo[1]) * (self.hi[2] - self.lo[2])
    }
}

fn mid(b: (f64, f64)) -> f64 {
    0.5 * (b.0 + b.1)
}

fn len(b: (f64, f64)) -> f64 {
    b.1 - b.0
}

impl Deform {
    /// A fix with these styles (lengths already in box units) made from the box `now`;
    /// checks the `volume` links with LIGGGHTS's error.
    pub fn new(
        every: i64,
        styles: [Style; 3],
        remap: Remap,
        now: BoxNow,
    ) -> Result<Deform, EngineError> {
        let vol = now.volume();
        let dims = styles.map(|style| Dim {
            style,
            link: None,
            initial: (0.0, 0.0),
            vol_initial: vol,
            start: (0.0, 0.0),
            vol_start: vol,
            stop: (0.0, 0.0),
            target: (0.0, 0.0),
        });
        let mut fix = Deform {
            every,
            dims,
            remap,
            h_rate: [0.0; 3],
            h_ratelo: [0.0; 3],
        };
        for i in 0..3 {
            fix.dims[i].initial = (now.lo[i], now.hi[i]);
            if fix.dims[i].style == Style::Volume {
                fix.dims[i].link = Some(fix.link(i)?);
            }
        }
        Ok(fix)
    }

    /// The dimensions a `volume` dimension `i` follows.
    fn link(&self, i: usize) -> Result<Link, EngineError> {
        const INVALID: &str = "Fix deform volume setting is invalid";
        let (o1, o2) = ((i + 1) % 3, (i + 2) % 3);
        let none = |k: usize| self.dims[k].style == Style::None;
        let volume = |k: usize| self.dims[k].style == Style::Volume;
        let free = |k: usize| !none(k) && !volume(k);
        if none(o1) {
            free(o2).then_some(Link::OneFromOne {
                fixed: o1,
                dynamic: o2,
            })
        } else if none(o2) {
            free(o1).then_some(Link::OneFromOne {
                fixed: o2,
                dynamic: o1,
            })
        } else if volume(o1) {
            free(o2).then_some(Link::TwoFromOne {
                fixed: o1,
                dynamic: o2,
            })
        } else if volume(o2) {
            free(o1).then_some(Link::TwoFromOne {
                fixed: o2,
                dynamic: o1,
            })
        } else {
            Some(Link::OneFromTwo(o1, o2))
        }
        .ok_or_else(|| INVALID.into())
    }

    /// Does the fix change dimension `d`?
    pub fn changes(&self, d: usize) -> bool {
        self.dims[d].style != Style::None
    }

    /// The variables the fix reads (`variable` styles): (length change, rate) per dimension.
    pub fn variables(&self) -> Vec<(&str, &str)> {
        self.dims
            .iter()
            .filter_map(|d| match &d.style {
                Style::Variable(a, b) => Some((a.as_str(), b.as_str())),
                _ => None,
            })
            .collect()
    }

    /// LIGGGHTS's `init` at a run's setup: the ramp from the box `now` (or, when the run's
    /// `start` lies before its first step, from the box at definition) over `delt` time
    /// units, and the constant edge rates.
    pub fn init(
        &mut self,
        now: BoxNow,
        from_definition: bool,
        delt: f64,
    ) -> Result<(), EngineError> {
        for i in 0..3 {
            let d = &mut self.dims[i];
            if from_definition {
                d.start = d.initial;
                d.vol_start = d.vol_initial;
            } else {
                d.start = (now.lo[i], now.hi[i]);
                d.vol_start = now.volume();
            }
            let (lo, hi) = d.start;
            let centre = mid(d.start);
            let length = len(d.start);
            d.stop = match &d.style {
                Style::Final(flo, fhi) => (*flo, *fhi),
                Style::Delta(dlo, dhi) => (lo + dlo, hi + dhi),
                Style::Scale(s) => (centre - 0.5 * s * length, centre + 0.5 * s * length),
                Style::Vel(v) => (lo - 0.5 * delt * v, hi + 0.5 * delt * v),
                Style::Erate(r) => {
                    let stop = (lo - 0.5 * delt * r * length, hi + 0.5 * delt * r * length);
                    if stop.1 <= stop.0 {
                        return Err("Final box dimension due to fix deform is < 0.0".into());
                    }
                    stop
                }
                Style::Trate(r) => {
                    let grown = length * (r * delt).exp();
                    (centre - 0.5 * grown, centre + 0.5 * grown)
                }
                Style::Wiggle(a, tp) => {
                    let s = (std::f64::consts::TAU * delt / tp).sin();
                    (lo - 0.5 * a * s, hi + 0.5 * a * s)
                }
                Style::None | Style::Volume | Style::Variable(..) => d.stop,
            };
            self.h_rate[i] = 0.0;
            self.h_ratelo[i] = 0.0;
            if matches!(
                d.style,
                Style::Final(..)
                    | Style::Delta(..)
                    | Style::Scale(_)
                    | Style::Vel(_)
                    | Style::Erate(_)
            ) {
                let (dlo, dhi) = if delt != 0.0 {
                    ((d.stop.0 - d.start.0) / delt, (d.stop.1 - d.start.1) / delt)
                } else {
                    (0.0, 0.0)
                };
                self.h_rate[i] = dhi - dlo;
                self.h_ratelo[i] = dlo;
            }
        }
        Ok(())
    }

    /// The bounds at this step (LIGGGHTS's `end_of_step` targets): `fraction` of the run
    /// done, `elapsed` time since its first step, `equal` evaluates the `variable` styles.
    pub fn targets(
        &mut self,
        now: BoxNow,
        fraction: f64,
        elapsed: f64,
        equal: &mut dyn FnMut(&str) -> Result<f64, EngineError>,
    ) -> Result<(), EngineError> {
        use std::f64::consts::TAU;
        for i in 0..3 {
            let length_now = now.hi[i] - now.lo[i];
            let d = &mut self.dims[i];
            let (centre, length) = (mid(d.start), len(d.start));
            match &d.style {
                Style::None => d.target = (now.lo[i], now.hi[i]),
                Style::Trate(r) => {
                    let grown = length * (r * elapsed).exp();
                    d.target = (centre - 0.5 * grown, centre + 0.5 * grown);
                    self.h_rate[i] = r * length_now;
                    self.h_ratelo[i] = -0.5 * self.h_rate[i];
                }
                Style::Wiggle(a, tp) => {
                    let s = (TAU * elapsed / tp).sin();
                    d.target = (d.start.0 - 0.5 * a * s, d.start.1 + 0.5 * a * s);
                    self.h_rate[i] = TAU / tp * a * (TAU * elapsed / tp).cos();
                    self.h_ratelo[i] = -0.5 * self.h_rate[i];
                }
                Style::Variable(disp, rate) => {
                    let del = equal(disp)?;
                    d.target = (d.start.0 - 0.5 * del, d.start.1 + 0.5 * del);
                    self.h_rate[i] = equal(rate)?;
                    self.h_ratelo[i] = -0.5 * self.h_rate[i];
                }
                Style::Volume => {}
                _ => {
                    d.target = (
                        d.start.0 + fraction * (d.stop.0 - d.start.0),
                        d.start.1 + fraction * (d.stop.1 - d.start.1),
                    );
                }
            }
        }
        for i in 0..3 {
            let Some(link) = self.dims[i].link else {
                continue;
            };
            let target_len = |k: usize| len(self.dims[k].target);
            let start_len = |k: usize| len(self.dims[k].start);
            let d = &self.dims[i];
            let half = match link {
                Link::OneFromOne { fixed, dynamic } => {
                    0.5 * (d.vol_start / target_len(dynamic) / start_len(fixed))
                }
                Link::OneFromTwo(a, b) => 0.5 * (d.vol_start / target_len(a) / target_len(b)),
                Link::TwoFromOne { fixed, dynamic } => {
                    0.5 * (d.vol_start / target_len(dynamic) / start_len(fixed) * len(d.start))
                        .sqrt()
                }
            };
            let centre = mid(d.start);
            self.dims[i].target = (centre - half, centre + half);
        }
        Ok(())
    }

    /// The box bounds after this step's change: the targets of the dimensions the fix
    /// changes, the current bounds of the others.
    pub fn new_box(&self, now: BoxNow) -> BoxNow {
        let mut out = now;
        for d in 0..3 {
            if self.changes(d) {
                (out.lo[d], out.hi[d]) = self.dims[d].target;
            }
        }
        out
    }
}

/// Carry `x` from box `old` to box `new` through its fractional coordinates (LIGGGHTS's
/// `x2lamda` in the old box, `lamda2x` in the new), every dimension.
pub fn remap_position(x: &mut [f64; 3], old: BoxNow, new: BoxNow) {
    for (d, xd) in x.iter_mut().enumerate() {
        let inv = 1.0 / (old.hi[d] - old.lo[d]);
        let lamda = inv * (*xd - old.lo[d]);
        *xd = (new.hi[d] - new.lo[d]) * lamda + new.lo[d];
    }
}

/// A periodic shift (a whole number of box lengths `old`) as the same number of lengths `new`.
pub fn rescale_shift(shift: &mut [f64; 3], old: [f64; 3], new: [f64; 3]) {
    for d in 0..3 {
        if shift[d] != 0.0 && old[d] != new[d] {
            let k = (shift[d] / old[d]).round();
            shift[d] = k * new[d];
        }
    }
}

impl crate::engine::fixes::FixStyle for Deform {
    fn name(&self) -> &str {
        "deform"
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn end_of_step_sim_due(&self, step: i64) -> bool {
        step % self.every == 0
    }

    fn end_of_step_sim(
        &mut self,
        sim: &mut crate::engine::sim::Simulation,
        k: usize,
        vars: &mut dyn crate::engine::sim::VariableSource,
    ) -> Result<(), EngineError> {
        sim.deform_apply(k, self, vars)
    }
}

impl crate::engine::sim::Simulation {
    /// The `fix deform` (LIGGGHTS allows one per run), as its index in the fix list.
    pub fn deform_fix(&self) -> Option<usize> {
        self.fixes
            .iter()
            .position(|f| f.kind.style_as::<Deform>().is_some())
    }

    /// Can the box change during a run (LIGGGHTS's `box_change`: a shrink-wrapped face or a
    /// `fix deform`)?
    pub fn box_changes(&self) -> bool {
        self.domain.shrinks() || self.deform_fix().is_some()
    }

    /// LIGGGHTS's init checks of `fix deform` (every run and `check`).
    pub fn check_deform(&self) -> Result<(), EngineError> {
        let deforms = self
            .fixes
            .iter()
            .filter(|f| f.kind.style_as::<Deform>().is_some());
        let Some(first) = deforms.clone().next() else {
            return Ok(());
        };
        if self
            .fixes
            .iter()
            .any(|f| f.kind.style_as::<crate::engine::clumps::Clumps>().is_some())
        {
            return Err(format!(
                "Fix deform (id {}): fix deform and fix multisphere are incompatible",
                first.id
            )
            .into());
        }
        if deforms.count() > 1 {
            return Err("More than one fix deform".into());
        }
        Ok(())
    }

    /// The run's setup (LIGGGHTS's `FixDeform::init`): the ramps over the run from `first`
    /// (the step the run starts at) and the run's bounds (`run ... start/stop`).
    pub fn setup_deform(&mut self, first: i64) -> Result<(), EngineError> {
        let bounds = self.run_bounds.unwrap_or((first, first));
        if let Some((k, f)) = self.deform_ramp(first, bounds)? {
            self.fixes[k].kind = crate::engine::fixes::FixKind::Style(Box::new(f));
        }
        Ok(())
    }

    /// `fix deform` set up for a run from step `first` with bounds (`begin`, `end`): its
    /// index and state, after LIGGGHTS's init checks (`check` makes them without running).
    pub fn deform_ramp(
        &self,
        first: i64,
        (begin, end): (i64, i64),
    ) -> Result<Option<(usize, Deform)>, EngineError> {
        self.check_deform()?;
        let Some(k) = self.deform_fix() else {
            return Ok(None);
        };
        let Some(f) = self.fixes[k].kind.style_as::<Deform>() else {
            return Ok(None);
        };
        let mut f = f.clone();
        let delt = (end - begin) as f64 * self.dt;
        let now = BoxNow {
            lo: self.domain.lo,
            hi: self.domain.hi,
        };
        f.init(now, first != begin, delt)?;
        Ok(Some((k, f)))
    }

    /// `fix deform`'s end of step (fix `k`, due at this step): move the box, carry the
    /// group's atoms along with `remap x`, and keep the neighbour list's periodic shifts
    /// whole box lengths.
    fn deform_apply(
        &mut self,
        k: usize,
        f: &mut Deform,
        vars: &mut dyn crate::engine::sim::VariableSource,
    ) -> Result<(), EngineError> {
        let (begin, end) = self.run_bounds.unwrap_or((self.step, self.step));
        let mut fraction = (self.step - begin) as f64;
        if fraction != 0.0 {
            fraction /= (end - begin) as f64;
        }
        let elapsed = (self.step - begin) as f64 * self.dt;
        let old = BoxNow {
            lo: self.domain.lo,
            hi: self.domain.hi,
        };
        {
            let sim = &*self;
            f.targets(old, fraction, elapsed, &mut |name| vars.equal(sim, name))?;
        }
        let new = f.new_box(old);
        if f.remap == Remap::X {
            let group = self.fixes[k].group;
            let p = &mut self.particles;
            for i in 0..p.len() {
                if p.mask[i] & group != 0 {
                    remap_position(&mut p.x[i], old, new);
                }
            }
        }
        self.domain.lo = new.lo;
        self.domain.hi = new.hi;
        let lengths = |b: BoxNow| [0, 1, 2].map(|d| b.hi[d] - b.lo[d]);
        let (l_old, l_new) = (lengths(old), lengths(new));
        for pair in &mut self.list.pairs {
            rescale_shift(&mut pair.shift, l_old, l_new);
        }
        for m in &mut self.list.mirrors {
            rescale_shift(&mut m.pair.shift, l_old, l_new);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> BoxNow {
        BoxNow {
            lo: [0.0; 3],
            hi: [1.0, 2.0, 4.0],
        }
    }

    #[test]
    fn ramps_and_volume() {
        let styles = [Style::Erate(-0.5), Style::Volume, Style::Final(0.0, 2.0)];
        let mut f = Deform::new(1, styles, Remap::X, unit()).unwrap();
        assert_eq!(f.dims[1].link, Some(Link::OneFromTwo(2, 0)));
        f.init(unit(), false, 1.0).unwrap();
        assert_eq!(f.dims[0].stop, (0.25, 0.75));
        assert_eq!(f.h_rate[0], -0.5);
        f.targets(unit(), 0.5, 0.5, &mut |_| unreachable!())
            .unwrap();
        assert_eq!(f.dims[0].target, (0.125, 0.875));
        assert_eq!(f.dims[2].target, (0.0, 3.0));
        // the volume (8) kept: y = 8 / (3 * 0.75)
        let y = len(f.dims[1].target);
        assert!((y - 8.0 / 2.25).abs() < 1e-15);
    }

    #[test]
    fn invalid_volume_and_negative_erate() {
        let styles = [Style::Volume, Style::None, Style::None];
        assert!(Deform::new(1, styles, Remap::X, unit()).is_err());
        let styles = [Style::Volume, Style::Volume, Style::Scale(2.0)];
        let f = Deform::new(1, styles, Remap::X, unit()).unwrap();
        assert_eq!(
            f.dims[0].link,
            Some(Link::TwoFromOne {
                fixed: 1,
                dynamic: 2
            })
        );
        let mut f = Deform::new(
            1,
            [Style::Erate(-3.0), Style::None, Style::None],
            Remap::X,
            unit(),
        )
        .unwrap();
        assert!(f.init(unit(), false, 1.0).is_err());
    }

    #[test]
    fn shifts_follow_the_box() {
        let mut s = [2.0, 0.0, -4.0];
        rescale_shift(&mut s, [2.0, 1.0, 4.0], [1.5, 1.0, 3.0]);
        assert_eq!(s, [1.5, 0.0, -3.0]);
        let mut x = [0.5, 1.0, 2.0];
        let new = BoxNow {
            lo: [0.0; 3],
            hi: [2.0, 2.0, 2.0],
        };
        remap_position(&mut x, unit(), new);
        assert_eq!(x, [1.0, 1.0, 1.0]);
    }
}
