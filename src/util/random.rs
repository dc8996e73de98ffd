//! The random-number generators whose streams LIGGGHTS decks depend on: Marsaglia's
//! lagged-Fibonacci generator (formula `random()`/`normal()` and many fixes) and the
//! Park–Miller minimal standard generator (displace_atoms, velocity, insertion). Both
//! reproduce LIGGGHTS 3.8.0's sequences bit for bit for the same seed.
//!
//! LIGGGHTS wraps every generator in a base class that first insists the user's seed is a
//! prime above 10000 ([`check_seed`]); the generators' own range checks come afterwards
//! ([`RanMars::new`], [`RanPark::new`]). Callers run both, in that order.

/// A seed LIGGGHTS refuses (its own words, hints included).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SeedError {
    /// Beyond a C `int` in either direction (LIGGGHTS blames INT_MAX for both).
    #[error("Seed {0} is larger than INT_MAX (2147483647)")]
    TooLarge(i64),
    /// Not a prime above 10000 (the message suggests valid seeds).
    #[error(
        "Random number generation: It is required that the random seed value is > 10000 \
         and a prime number.\nThe random seed used was {0}\n  Hint 1: start with \
         'liggghts -echo both < in.script' to find out which command caused this\n  \
         Hint 2: possible valid seeds would be the following numbers:\n          \
         15485863, 15485867, 32452843, 32452867, 49979687, 49979693, \
                               67867967, 67867979, 86028121, 86028157"
    )]
    NotPrime(i64),
    /// Marsaglia's generator needs a seed in 1..=900000000.
    #[error("Invalid seed for Marsaglia random # generator")]
    Marsaglia,
    /// Park and Miller's generator needs a positive seed.
    #[error("Invalid seed for Park random # generator")]
    Park,
}

/// The message alone, for callers that still report errors as text.
impl From<SeedError> for String {
    fn from(e: SeedError) -> String {
        e.to_string()
    }
}

/// LIGGGHTS's rule for user seeds: a prime above 10000 that fits a C `int` (relaxed to a
/// warning by `-seedtolerant`); the error text is LIGGGHTS's own, hints included.
pub fn check_seed(seed: i64) -> Result<(), SeedError> {
    if seed > i32::MAX as i64 || seed < i32::MIN as i64 {
        // LIGGGHTS compares atol() with atoi() and blames INT_MAX for either direction
        return Err(SeedError::TooLarge(seed));
    }
    if seed < 10000 || !is_prime(seed) {
        return Err(SeedError::NotPrime(seed));
    }
    Ok(())
}

/// Whether `n` is prime (trial division; LIGGGHTS seeds are at most 2^31 - 1).
pub fn is_prime(n: i64) -> bool {
    if n < 2 {
        return false;
    }
    if n < 4 {
        return true;
    }
    if n % 2 == 0 || n % 3 == 0 {
        return false;
    }
    // candidates 6k - 1 and 6k + 1
    let mut d = 5;
    while d * d <= n {
        if n % d == 0 || n % (d + 2) == 0 {
            return false;
        }
        d += 6;
    }
    true
}

/// One polar Box–Muller step: draw points in the unit disc (rejecting the rim and the
/// centre) and return the two normal deviates as (first, second), in LIGGGHTS's order.
fn polar_pair(mut uniform: impl FnMut() -> f64) -> (f64, f64) {
    loop {
        let v1 = 2.0 * uniform() - 1.0;
        let v2 = 2.0 * uniform() - 1.0;
        let rsq = v1 * v1 + v2 * v2;
        if rsq < 1.0 && rsq != 0.0 {
            let fac = (-2.0 * rsq.ln() / rsq).sqrt();
            // the deviate from v2 is handed out now, the one from v1 on the next call
            return (v2 * fac, v1 * fac);
        }
    }
}

/// Marsaglia's RANMAR generator (F. James, Comp. Phys. Comm. 60, 329 (1990)) as LIGGGHTS
/// uses it: uniform deviates in [0, 1) and unit normal deviates.
#[derive(Debug, Clone)]
pub struct RanMars {
    /// Lag table, slots 1..=97 (slot 0 unused, as in the Fortran original).
    lags: [f64; 98],
    i97: usize,
    j97: usize,
    carry: f64,
    carry_step: f64,
    carry_mod: f64,
    /// Second normal deviate of the last Box–Muller pair, not yet handed out.
    spare: Option<f64>,
}

impl RanMars {
    /// A generator for `seed` in 1..=900000000 (else LIGGGHTS's error text); the first
    /// uniform deviate is drawn and discarded, as LIGGGHTS does.
    pub fn new(seed: i32) -> Result<RanMars, SeedError> {
        if seed <= 0 || seed > 900_000_000 {
            return Err(SeedError::Marsaglia);
        }
        // split the seed into the four small seeds of the lagged-Fibonacci initialisation
        let ij = (seed - 1) / 30082;
        let kl = (seed - 1) - 30082 * ij;
        let mut i = (ij / 177) % 177 + 2;
        let mut j = ij % 177 + 2;
        let mut k = (kl / 169) % 178 + 1;
        let mut l = kl % 169;
        let mut lags = [0.0; 98];
        for slot in lags.iter_mut().skip(1) {
            let mut value = 0.0;
            let mut bit = 0.5;
            for _ in 0..24 {
                let m = ((i * j) % 179) * k % 179;
                i = j;
                j = k;
                k = m;
                l = (53 * l + 1) % 169;
                if (l * m) % 64 >= 32 {
                    value += bit;
                }
                bit *= 0.5;
            }
            *slot = value;
        }
        let mut r = RanMars {
            lags,
            i97: 97,
            j97: 33,
            carry: 362436.0 / 16777216.0,
            carry_step: 7654321.0 / 16777216.0,
            carry_mod: 16777213.0 / 16777216.0,
            spare: None,
        };
        r.uniform();
        Ok(r)
    }

    /// Next uniform deviate, in [0, 1) (multiples of 2^-24).
    pub fn uniform(&mut self) -> f64 {
        let mut uni = self.lags[self.i97] - self.lags[self.j97];
        if uni < 0.0 {
            uni += 1.0;
        }
        self.lags[self.i97] = uni;
        self.i97 = if self.i97 == 1 { 97 } else { self.i97 - 1 };
        self.j97 = if self.j97 == 1 { 97 } else { self.j97 - 1 };
        self.carry -= self.carry_step;
        if self.carry < 0.0 {
            self.carry += self.carry_mod;
        }
        uni -= self.carry;
        if uni < 0.0 {
            uni += 1.0;
        }
        uni
    }

    /// Next normal deviate (mean 0, standard deviation 1); deviates come in Box–Muller
    /// pairs and the second of a pair is returned by the following call.
    pub fn gaussian(&mut self) -> f64 {
        if let Some(v) = self.spare.take() {
            return v;
        }
        let (first, second) = polar_pair(|| self.uniform());
        self.spare = Some(second);
        first
    }
}

/// Park–Miller multiplier.
const PARK_A: i32 = 16807;
/// Park–Miller modulus, 2^31 - 1.
const PARK_M: i32 = 2147483647;
/// Schrage's decomposition of the modulus: M = A*Q + R.
const PARK_Q: i32 = 127773;
const PARK_R: i32 = 2836;

/// The Park–Miller "minimal standard" generator as LIGGGHTS uses it: uniform deviates in
/// (0, 1), unit normal deviates, and reseeding from a position.
#[derive(Debug, Clone)]
pub struct RanPark {
    state: i32,
    /// Second normal deviate of the last Box–Muller pair, not yet handed out.
    spare: Option<f64>,
}

impl RanPark {
    /// A generator for a positive `seed` (else LIGGGHTS's error text).
    pub fn new(seed: i32) -> Result<RanPark, SeedError> {
        if seed <= 0 {
            return Err(SeedError::Park);
        }
        Ok(RanPark {
            state: seed,
            spare: None,
        })
    }

    /// Next uniform deviate, in (0, 1) (the new state divided by 2^31 - 1).
    pub fn uniform(&mut self) -> f64 {
        // Schrage's method keeps state * A inside 32 bits
        let k = self.state / PARK_Q;
        self.state = PARK_A * (self.state - k * PARK_Q) - PARK_R * k;
        if self.state < 0 {
            self.state += PARK_M;
        }
        self.state as f64 * (1.0 / PARK_M as f64)
    }

    /// Next normal deviate (mean 0, standard deviation 1), in Box–Muller pairs like
    /// [`RanMars::gaussian`].
    pub fn gaussian(&mut self) -> f64 {
        if let Some(v) = self.spare.take() {
            return v;
        }
        let (first, second) = polar_pair(|| self.uniform());
        self.spare = Some(second);
        first
    }

    /// Restart from a new positive seed, dropping any saved normal deviate.
    pub fn reset(&mut self, seed: i32) -> Result<(), SeedError> {
        *self = RanPark::new(seed)?;
        Ok(())
    }

    /// Reseed from a base seed and a position, so that the stream an atom sees does not
    /// depend on which process owns it: Jenkins' one-at-a-time hash over the bytes of
    /// `base` and of the three coordinates (each byte read as a signed C `char`), reduced
    /// to 27 bits (0 becomes 1), followed by five discarded draws.
    pub fn reset_at(&mut self, base: i32, coord: [f64; 3]) {
        let mut hash: u32 = 0;
        let mut mix = |byte: u8| {
            hash = hash.wrapping_add(byte as i8 as i32 as u32);
            hash = hash.wrapping_add(hash << 10);
            hash ^= hash >> 6;
        };
        base.to_ne_bytes().into_iter().for_each(&mut mix);
        coord
            .iter()
            .flat_map(|c| c.to_ne_bytes())
            .for_each(&mut mix);
        hash = hash.wrapping_add(hash << 3);
        hash ^= hash >> 11;
        hash = hash.wrapping_add(hash << 15);
        // LIGGGHTS's mask keeps 27 bits, although its comment speaks of 31
        self.state = (hash & 0x07ff_ffff) as i32;
        if self.state == 0 {
            self.state = 1;
        }
        for _ in 0..5 {
            self.uniform();
        }
        self.spare = None;
    }

    /// The current internal state (what the next draw starts from), in 1..2^31 - 1.
    pub fn state(&self) -> i32 {
        self.state
    }
}

#[cfg(test)]
// expected values are copied digit for digit from LIGGGHTS's %.17g output
#[allow(clippy::excessive_precision)]
mod tests {
    use super::*;

    /// Parse numbers LIGGGHTS printed with %.20g (enough digits to name the double exactly).
    fn doubles(text: &str) -> Vec<f64> {
        text.split_whitespace()
            .map(|w| w.parse().unwrap())
            .collect()
    }

    // liggghts -in in.u, in.u being:  print "$(random(0,1,S)) ... (10 times)"
    // (`$(...)` prints %.20g of the raw value; random(0,1,S) is exactly uniform()).
    const MARS_UNIFORM: [(i32, &str); 3] = [
        (
            15485863,
            "0.86316907405853271484 0.6564229130744934082 0.88727664947509765625 \
             0.47164058685302734375 0.91796869039535522461 0.79044377803802490234 \
             0.44426465034484863281 0.3881842494010925293 0.62760913372039794922 \
             0.94542384147644042969",
        ),
        (
            32452843,
            "0.10641717910766601562 0.96278554201126098633 0.72677642107009887695 \
             0.0076922178268432617188 0.75859314203262329102 0.88885927200317382812 \
             0.73705828189849853516 0.12769240140914916992 0.43149292469024658203 \
             0.42939096689224243164",
        ),
        (
            86028121,
            "0.3304068446159362793 0.64602875709533691406 0.2968514561653137207 \
             0.95473277568817138672 0.95700442790985107422 0.57355344295501708984 \
             0.053451836109161376953 0.23389452695846557617 0.19636327028274536133 \
             0.91546022891998291016",
        ),
    ];

    // the same with  print "$(normal(0,1,S)) ... (6 times)"  in a fresh run
    const MARS_NORMAL: [(i32, &str); 3] = [
        (
            15485863,
            "0.38324647910204878709 0.88978824275827483881 -0.07343932932251691359 \
             1.0028887851919012775 -2.1078988745379549918 -1.050697063524616448",
        ),
        (
            32452843,
            "0.43521824179972656843 0.28942206273529902383 -0.59579022218998201055 \
             0.37935569131237334428 -1.830232688882594605 -1.7757485569913138423",
        ),
        (
            86028121,
            "1.1700345210226990034 -1.3588408904896278617 0.11422473583557039845 \
             -0.05102906585033614717 0.088260265068177190528 0.54838129017729220216",
        ),
    ];

    #[test]
    fn marsaglia_uniform_matches_liggghts() {
        for (seed, text) in MARS_UNIFORM {
            let mut r = RanMars::new(seed).unwrap();
            for want in doubles(text) {
                assert_eq!(r.uniform(), want, "seed {seed}");
            }
        }
    }

    #[test]
    fn marsaglia_gaussian_matches_liggghts() {
        for (seed, text) in MARS_NORMAL {
            let mut r = RanMars::new(seed).unwrap();
            for want in doubles(text) {
                assert_eq!(r.gaussian(), want, "seed {seed}");
            }
        }
    }

    #[test]
    fn marsaglia_mixed_draws_share_one_stream() {
        // print "$(random(0,1,S)) $(normal(0,1,S)) $(random(0,1,S)) $(normal(0,1,S))
        //        $(normal(0,1,S)) $(random(0,1,S))"  with S = 15485863
        let want = doubles(
            "0.86316907405853271484 0.78657270464517692332 0.47164058685302734375 \
             0.31770052228101908209 -2.1078988745379549918 0.62760913372039794922",
        );
        let mut r = RanMars::new(15485863).unwrap();
        let got = [
            r.uniform(),
            r.gaussian(),
            r.uniform(),
            r.gaussian(),
            r.gaussian(),
            r.uniform(),
        ];
        assert_eq!(got.to_vec(), want);
    }

    #[test]
    fn park_miller_published_check() {
        // Park & Miller (1988): seed 1 reaches 1043618065 after 10000 draws
        let mut r = RanPark::new(1).unwrap();
        for _ in 0..10000 {
            r.uniform();
        }
        assert_eq!(r.state(), 1043618065);
        let mut r = RanPark::new(1).unwrap();
        assert_eq!(r.uniform(), 16807.0 * (1.0 / 2147483647.0));
        assert_eq!(r.state(), 16807);
    }

    #[test]
    fn park_reset_at_matches_displace_atoms() {
        // liggghts: atoms at (0.5,0.5,0.5) and (0.25,0.125,0.75), then
        //   displace_atoms all random 0.5 0.25 0.125 32452843 units box
        // which does reset_at(seed, x) and x += d * 2 * (uniform() - 0.5) per coordinate;
        // positions written with %.17g
        let cases = [
            (
                [0.5, 0.5, 0.5],
                [
                    0.49750309414114013,
                    0.51725161507132067,
                    0.47394725184372966,
                ],
            ),
            (
                [0.25, 0.125, 0.75],
                [
                    -0.10764131036477226,
                    0.1862483496364431,
                    0.70050616984977676,
                ],
            ),
        ];
        let d = [0.5, 0.25, 0.125];
        let mut r = RanPark::new(32452843).unwrap();
        for (start, want) in cases {
            r.reset_at(32452843, start);
            for k in 0..3 {
                let moved = start[k] + d[k] * 2.0 * (r.uniform() - 0.5);
                assert_eq!(moved, want[k], "coordinate {k} of {start:?}");
            }
        }
    }

    #[test]
    fn park_gaussian_pairs() {
        let mut a = RanPark::new(15485863).unwrap();
        let mut b = a.clone();
        let (first, second) = polar_pair(|| b.uniform());
        assert_eq!(a.gaussian(), first);
        assert_eq!(a.gaussian(), second);
        a.reset(15485863).unwrap();
        assert_eq!(a.gaussian(), first);
        assert!(a.reset(0).is_err());
    }

    #[test]
    fn seeds() {
        assert_eq!(
            RanMars::new(0).unwrap_err().to_string(),
            "Invalid seed for Marsaglia random # generator"
        );
        assert!(RanMars::new(900_000_001).is_err());
        assert!(RanMars::new(900_000_000).is_ok());
        assert_eq!(
            RanPark::new(-5).unwrap_err().to_string(),
            "Invalid seed for Park random # generator"
        );
        assert!(check_seed(15485863).is_ok());
        assert!(check_seed(2147483647).is_ok());
        // print "$(random(0,1,12345))" in liggghts:
        let e = check_seed(12345).unwrap_err().to_string();
        assert!(e.starts_with(
            "Random number generation: It is required that the random seed value is > 10000 \
             and a prime number.\nThe random seed used was 12345\n  Hint 1: start with"
        ));
        assert!(e.ends_with("67867967, 67867979, 86028121, 86028157"));
        assert!(check_seed(7).is_err());
        assert_eq!(
            check_seed(3_000_000_000).unwrap_err().to_string(),
            "Seed 3000000000 is larger than INT_MAX (2147483647)"
        );
    }

    #[test]
    fn primes() {
        let small: Vec<i64> = (0..40).filter(|&n| is_prime(n)).collect();
        assert_eq!(small, [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37]);
        assert!(is_prime(86028157));
        assert!(!is_prime(86028157 * 3));
        assert!(!is_prime(10007 * 10009));
    }

    #[test]
    fn marsaglia_moments() {
        let mut r = RanMars::new(15485863).unwrap();
        let n = 20000;
        let mean: f64 = (0..n).map(|_| r.uniform()).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.01);
        let g: Vec<f64> = (0..n).map(|_| r.gaussian()).collect();
        let m = g.iter().sum::<f64>() / n as f64;
        let v = g.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / n as f64;
        assert!(m.abs() < 0.03 && (v - 1.0).abs() < 0.05, "{m} {v}");
    }
}
