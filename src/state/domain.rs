//! The simulation box: bounds, boundary conditions per face (`p`, `f`, `s`, `m`),
//! periodic wrapping with image counts, and shrink-wrapping, as LIGGGHTS does them.

/// How one face of the box behaves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// `p`: periodic (both faces of the direction).
    Periodic,
    /// `f`: fixed; particles crossing it are lost.
    Fixed,
    /// `s`: shrink-wrapped to the particles.
    Shrink,
    /// `m`: shrink-wrapped, but never inside the initial face position.
    ShrinkMin,
}

impl Boundary {
    fn letter(self) -> char {
        match self {
            Boundary::Periodic => 'p',
            Boundary::Fixed => 'f',
            Boundary::Shrink => 's',
            Boundary::ShrinkMin => 'm',
        }
    }
}

/// Padding LIGGGHTS adds around shrink-wrapped extents, as a fraction of the initial length.
const SHRINK_PAD: f64 = 1.0e-4;

/// The box (lengths in box units).
#[derive(Debug, Clone, PartialEq)]
pub struct Domain {
    /// True once `create_box` (or a data/restart file) has made the box.
    pub exists: bool,
    /// Lower corner.
    pub lo: [f64; 3],
    /// Upper corner.
    pub hi: [f64; 3],
    /// Boundary of the lower and upper face in each direction.
    pub boundary: [[Boundary; 2]; 3],
    /// Face positions at creation, the limits for `m` faces.
    initial_lo: [f64; 3],
    initial_hi: [f64; 3],
    /// Shrink-wrap padding per direction (fixed at creation).
    pad: [f64; 3],
}

impl Default for Domain {
    fn default() -> Self {
        Domain {
            exists: false,
            lo: [-0.5; 3],
            hi: [0.5; 3],
            boundary: [[Boundary::Periodic; 2]; 3],
            initial_lo: [-0.5; 3],
            initial_hi: [0.5; 3],
            pad: [0.0; 3],
        }
    }
}

/// Why a box or its boundaries are refused (LIGGGHTS's messages).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BoxError {
    /// `boundary` without three words.
    #[error("Illegal boundary command")]
    BoundaryCount,
    /// A boundary word other than p, f, s, m or two of them.
    #[error("Illegal boundary command: '{0}' (expected p, f, s, m or two of them)")]
    BoundaryWord(String),
    /// One side periodic, the other not.
    #[error("Both sides of boundary must be periodic")]
    HalfPeriodic,
    /// Shrink-wrapping turned the box inside out.
    #[error("Illegal simulation box")]
    InsideOut,
    /// Box bounds that enclose no volume (or are not numbers).
    #[error("Box bounds are invalid")]
    InvalidBounds,
}

/// Parse the `boundary` command's three words (e.g. `p f fm`).
pub fn parse_boundary(words: &[&str]) -> Result<[[Boundary; 2]; 3], BoxError> {
    if words.len() != 3 {
        return Err(BoxError::BoundaryCount);
    }
    let mut out = [[Boundary::Periodic; 2]; 3];
    for (d, w) in words.iter().enumerate() {
        let chars: Vec<char> = w.chars().collect();
        let pair = match chars.as_slice() {
            [c] => [*c, *c],
            [a, b] => [*a, *b],
            _ => return Err(BoxError::BoundaryWord(w.to_string())),
        };
        for (side, c) in pair.iter().enumerate() {
            out[d][side] = match c {
                'p' => Boundary::Periodic,
                'f' => Boundary::Fixed,
                's' => Boundary::Shrink,
                'm' => Boundary::ShrinkMin,
                _ => return Err(BoxError::BoundaryWord(w.to_string())),
            };
        }
        if (out[d][0] == Boundary::Periodic) != (out[d][1] == Boundary::Periodic) {
            return Err(BoxError::HalfPeriodic);
        }
    }
    Ok(out)
}

/// Wrap one periodic coordinate into `[lo, hi)`, counting images; false if it is not finite.
fn wrap(x: &mut f64, image: &mut i32, lo: f64, hi: f64) -> bool {
    if !x.is_finite() {
        return false;
    }
    let period = hi - lo;
    if *x < lo {
        *x += period;
        *image = image.wrapping_sub(1);
    } else if *x >= hi {
        *x -= period;
        *image = image.wrapping_add(1);
    }
    if *x < lo || *x >= hi {
        // more than a period away: move by whole periods at once
        let periods = ((*x - lo) / period).floor();
        *x -= periods * period;
        // beyond i32 only the low bits can be kept (restart files store 10 of them)
        let step = if periods.abs() < 1.0e9 {
            periods as i32
        } else {
            (periods % 1024.0) as i32
        };
        *image = image.wrapping_add(step);
        if !(*x >= lo && *x < hi) {
            // rounding left it just outside (or the period is lost in the magnitude)
            *x = lo;
        }
    }
    *x = x.max(lo);
    true
}

impl Domain {
    /// Make the box with the given corners (the `create_box` step).
    pub fn create(&mut self, lo: [f64; 3], hi: [f64; 3]) {
        self.exists = true;
        self.lo = lo;
        self.hi = hi;
        self.initial_lo = lo;
        self.initial_hi = hi;
        for d in 0..3 {
            self.pad[d] = SHRINK_PAD * (hi[d] - lo[d]);
        }
    }

    /// True if direction `d` is periodic.
    pub fn periodic(&self, d: usize) -> bool {
        self.boundary[d][0] == Boundary::Periodic
    }

    /// Box length in direction `d`.
    pub fn length(&self, d: usize) -> f64 {
        self.hi[d] - self.lo[d]
    }

    /// The boundary letters as dumps print them, e.g. `pp ff fm`.
    pub fn boundary_label(&self) -> String {
        let parts: Vec<String> = self
            .boundary
            .iter()
            .map(|b| format!("{}{}", b[0].letter(), b[1].letter()))
            .collect();
        parts.join(" ")
    }

    /// Wrap a position into the box along periodic directions, counting images. Returns false
    /// (and leaves that coordinate alone) when a periodic coordinate is not finite: such an
    /// atom cannot be placed anywhere in the box and is lost.
    ///
    /// A coordinate within a period of the box moves by one period, exactly as LIGGGHTS's
    /// loop moves it; one farther away moves by a whole number of periods at once (floor
    /// division), so a huge coordinate costs no more than a near one.
    pub fn remap(&self, x: &mut [f64; 3], image: &mut [i32; 3]) -> bool {
        let mut placed = true;
        for d in 0..3 {
            if self.periodic(d) && !wrap(&mut x[d], &mut image[d], self.lo[d], self.hi[d]) {
                placed = false;
            }
        }
        placed
    }

    /// LIGGGHTS's `remap_near`: move `xnew` by whole periods along periodic dimensions to
    /// the image nearest `xold` (length), as `fix move` does after prescribing a position
    /// from an unwrapped start point. Non-finite coordinates are left alone.
    pub fn remap_near(&self, xnew: &mut [f64; 3], xold: &[f64; 3]) {
        for d in 0..3 {
            if !self.periodic(d) || !(xnew[d] - xold[d]).is_finite() {
                continue;
            }
            let period = self.length(d);
            let half = 0.5 * period;
            if xnew[d] - xold[d] > period {
                let n = ((xnew[d] - xold[d]) / period) as i64;
                xnew[d] -= n as f64 * period;
            }
            // at most two more periods after the jump above (bounded, unlike a bare loop)
            for _ in 0..4 {
                if xnew[d] - xold[d] > half {
                    xnew[d] -= period;
                } else {
                    break;
                }
            }
            if xold[d] - xnew[d] > period {
                let n = ((xold[d] - xnew[d]) / period) as i64;
                xnew[d] += n as f64 * period;
            }
            for _ in 0..4 {
                if xold[d] - xnew[d] > half {
                    xnew[d] += period;
                } else {
                    break;
                }
            }
        }
    }

    /// Shortest periodic image of a separation vector.
    pub fn minimum_image(&self, delta: &mut [f64; 3]) {
        for (d, component) in delta.iter_mut().enumerate() {
            if self.periodic(d) {
                let period = self.length(d);
                if component.abs() > 0.5 * period {
                    if *component < 0.0 {
                        *component += period;
                    } else {
                        *component -= period;
                    }
                }
            }
        }
    }

    /// Shrink-wrap the `s`/`m` faces around `extent` (min and max of positions, and of
    /// anything else that bounds the box such as walls); errors if the box turns inside out.
    pub fn shrink_wrap(
        &mut self,
        extent_lo: [f64; 3],
        extent_hi: [f64; 3],
    ) -> Result<(), BoxError> {
        for d in 0..3 {
            if self.periodic(d) {
                continue;
            }
            match self.boundary[d][0] {
                Boundary::Shrink => self.lo[d] = extent_lo[d] - self.pad[d],
                Boundary::ShrinkMin => {
                    self.lo[d] = (extent_lo[d] - self.pad[d]).min(self.initial_lo[d])
                }
                _ => {}
            }
            match self.boundary[d][1] {
                Boundary::Shrink => self.hi[d] = extent_hi[d] + self.pad[d],
                Boundary::ShrinkMin => {
                    self.hi[d] = (extent_hi[d] + self.pad[d]).max(self.initial_hi[d])
                }
                _ => {}
            }
            if self.lo[d] > self.hi[d] {
                return Err(BoxError::InsideOut);
            }
        }
        Ok(())
    }

    /// LIGGGHTS's `set_initial_box` after the box was changed in place (`change_box`): the
    /// bounds must enclose a volume, the shrink-wrap padding becomes 1e-4 of each current
    /// length, `s` faces move out by it and `m` faces take their current position as limit.
    pub fn reset_initial(&mut self) -> Result<(), BoxError> {
        // a NaN bound fails the negated comparison too
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        let invalid = (0..3).any(|d| !(self.lo[d] < self.hi[d]));
        if invalid {
            return Err(BoxError::InvalidBounds);
        }
        for d in 0..3 {
            self.pad[d] = SHRINK_PAD * (self.hi[d] - self.lo[d]);
            match self.boundary[d][0] {
                Boundary::Shrink => self.lo[d] -= self.pad[d],
                Boundary::ShrinkMin => self.initial_lo[d] = self.lo[d],
                _ => {}
            }
            match self.boundary[d][1] {
                Boundary::Shrink => self.hi[d] += self.pad[d],
                Boundary::ShrinkMin => self.initial_hi[d] = self.hi[d],
                _ => {}
            }
        }
        Ok(())
    }

    /// Does any face shrink-wrap?
    pub fn shrinks(&self) -> bool {
        self.boundary
            .iter()
            .flatten()
            .any(|b| matches!(b, Boundary::Shrink | Boundary::ShrinkMin))
    }

    /// Is `x` inside the box along every non-periodic direction (lost-atom test)?
    pub fn contains(&self, x: [f64; 3]) -> bool {
        (0..3).all(|d| self.periodic(d) || (x[d] >= self.lo[d] && x[d] < self.hi[d]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remap_near_picks_the_nearest_image_and_ends() {
        let mut d = Domain {
            boundary: parse_boundary(&["p", "p", "f"]).unwrap(),
            ..Domain::default()
        };
        d.create([0.0; 3], [1.0, 2.0, 3.0]);
        let mut x = [1.2, -3.9, 5.0];
        d.remap_near(&mut x, &[0.1, 0.1, 0.0]);
        assert!(
            (x[0] - 0.2).abs() < 1e-12 && (x[1] - 0.1).abs() < 1e-12,
            "{x:?}"
        );
        assert_eq!(x[2], 5.0);
        // far away and non-finite values terminate
        let mut far = [1e300, f64::INFINITY, 0.0];
        d.remap_near(&mut far, &[0.5, 0.5, 0.0]);
        assert!(far[1].is_infinite());
    }

    #[test]
    fn boundary_words() {
        let b = parse_boundary(&["p", "f", "fm"]).unwrap();
        let mut d = Domain {
            boundary: b,
            ..Domain::default()
        };
        d.create([0.0; 3], [1.0, 2.0, 3.0]);
        assert_eq!(d.boundary_label(), "pp ff fm");
        assert!(parse_boundary(&["pf", "f", "f"]).is_err());
        assert!(parse_boundary(&["x", "f", "f"]).is_err());
        assert!(parse_boundary(&["p", "f"]).is_err());
    }

    #[test]
    fn wrap_and_shrink() {
        let mut d = Domain {
            boundary: parse_boundary(&["p", "s", "fm"]).unwrap(),
            ..Domain::default()
        };
        d.create([0.0; 3], [1.0, 1.0, 1.0]);
        let mut x = [1.25, 0.5, 0.5];
        let mut img = [0; 3];
        assert!(d.remap(&mut x, &mut img));
        assert_eq!((x[0], img[0]), (0.25, 1));
        let mut delta = [0.9, 0.0, 0.0];
        d.minimum_image(&mut delta);
        assert!((delta[0] + 0.1).abs() < 1e-15);
        d.shrink_wrap([0.0, 0.2, 0.1], [1.0, 0.4, 0.5]).unwrap();
        assert!((d.lo[1] - (0.2 - 1e-4)).abs() < 1e-15 && (d.hi[1] - (0.4 + 1e-4)).abs() < 1e-15);
        assert_eq!(d.hi[2], 1.0); // m face never moves inside its initial position
        d.shrink_wrap([0.0, 0.2, 0.1], [1.0, 0.4, 2.0]).unwrap();
        assert!((d.hi[2] - (2.0 + 1e-4)).abs() < 1e-15);
    }

    #[test]
    fn wrap_is_o1_and_loses_non_finite() {
        let mut d = Domain {
            boundary: parse_boundary(&["p", "p", "f"]).unwrap(),
            ..Domain::default()
        };
        d.create([0.0; 3], [1.0, 1.0, 1.0]);
        // far coordinates wrap at once, into the box
        for far in [
            1e300,
            -1e300,
            1e17 + 0.5,
            -7.25,
            1234.5,
            f64::MAX,
            -f64::MAX,
        ] {
            let mut x = [far, 0.5, 0.5];
            let mut img = [0; 3];
            assert!(d.remap(&mut x, &mut img), "{far}");
            assert!(x[0] >= 0.0 && x[0] < 1.0, "{far} -> {}", x[0]);
        }
        let mut x = [-7.25, 0.5, 0.5];
        let mut img = [0; 3];
        d.remap(&mut x, &mut img);
        assert_eq!((x[0], img[0]), (0.75, -8));
        // one period away: exactly LIGGGHTS's single step
        let mut x = [-0.1, 1.1, 0.5];
        let mut img = [0; 3];
        d.remap(&mut x, &mut img);
        assert_eq!(x, [-0.1 + 1.0, 1.1 - 1.0, 0.5]);
        assert_eq!(img, [-1, 1, 0]);
        // not finite: not placed (the atom is lost), never the lower bound
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut x = [bad, 0.5, 0.5];
            let mut img = [0; 3];
            assert!(!d.remap(&mut x, &mut img));
            assert!(!x[0].is_finite());
        }
        // a non-finite coordinate along a fixed direction is the lost-atom test's business
        let mut x = [0.5, 0.5, f64::NAN];
        assert!(d.remap(&mut x, &mut [0; 3]));
        assert!(!d.contains(x));
    }
}
