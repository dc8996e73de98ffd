//! The random-number generators whose streams LIGGGHTS decks depend on: Marsaglia's
//! lagged-Fibonacci generator (formula `random()`/`normal()`, many fixes) and the Park–Miller
//! minimal standard generator (insertion, velocity). Both reproduce LIGGGHTS's sequences bit
//! for bit for the same seed.

/// LIGGGHTS's rule for user seeds: above 10000 and prime (relaxed by `-seedtolerant`).
pub fn check_seed(seed: i64) -> Result<(), String> {
    if seed > i32::MAX as i64 {
        return Err(format!("Seed {seed} is larger than INT_MAX ({})", i32::MAX));
    }
    if seed < 10000 || !is_prime(seed) {
        return Err(format!(
            "Random number generation: It is required that the random seed value is > 10000 and a prime number. \
             The random seed used was {seed}"
        ));
    }
    Ok(())
}

/// Trial division primality test (seeds are at most 2^31).
pub fn is_prime(n: i64) -> bool {
    if n < 2 {
        return false;
    }
    if n % 2 == 0 {
        return n == 2;
    }
    let mut d = 3;
    while d * d <= n {
        if n % d == 0 {
            return false;
        }
        d += 2;
    }
    true
}

/// Marsaglia's universal generator (uniform in [0,1)), with Box–Muller gaussians.
#[derive(Debug, Clone)]
pub struct RanMars {
    table: [f64; 98],
    i97: usize,
    j97: usize,
    c: f64,
    cd: f64,
    cm: f64,
    spare: Option<f64>,
}

impl RanMars {
    /// Seed the generator; valid seeds are 1..=900000000.
    pub fn new(seed: i32) -> Result<RanMars, String> {
        if seed <= 0 || seed > 900_000_000 {
            return Err("Invalid seed for Marsaglia random # generator".into());
        }
        let ij = (seed - 1) / 30082;
        let kl = (seed - 1) - 30082 * ij;
        let mut i = (ij / 177) % 177 + 2;
        let mut j = ij % 177 + 2;
        let mut k = (kl / 169) % 178 + 1;
        let mut l = kl % 169;
        let mut table = [0.0; 98];
        for slot in table.iter_mut().skip(1) {
            let mut s = 0.0;
            let mut t = 0.5;
            for _ in 0..24 {
                let m = ((i * j) % 179) * k % 179;
                i = j;
                j = k;
                k = m;
                l = (53 * l + 1) % 169;
                if (l * m) % 64 >= 32 {
                    s += t;
                }
                t *= 0.5;
            }
            *slot = s;
        }
        let mut r = RanMars {
            table,
            i97: 97,
            j97: 33,
            c: 362436.0 / 16777216.0,
            cd: 7654321.0 / 16777216.0,
            cm: 16777213.0 / 16777216.0,
            spare: None,
        };
        r.uniform(); // LIGGGHTS discards the first value
        Ok(r)
    }

    /// Next uniform deviate in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        let mut uni = self.table[self.i97] - self.table[self.j97];
        if uni < 0.0 {
            uni += 1.0;
        }
        self.table[self.i97] = uni;
        self.i97 = if self.i97 == 1 { 97 } else { self.i97 - 1 };
        self.j97 = if self.j97 == 1 { 97 } else { self.j97 - 1 };
        self.c -= self.cd;
        if self.c < 0.0 {
            self.c += self.cm;
        }
        uni -= self.c;
        if uni < 0.0 {
            uni += 1.0;
        }
        uni
    }

    /// Next standard normal deviate (mean 0, variance 1); pairs are generated together.
    pub fn gaussian(&mut self) -> f64 {
        if let Some(v) = self.spare.take() {
            return v;
        }
        let (v1, v2, rsq) = polar_pair(|| self.uniform());
        let fac = (-2.0 * rsq.ln() / rsq).sqrt();
        self.spare = Some(v1 * fac);
        v2 * fac
    }
}

/// Draw points in the unit disc (polar Box–Muller) until one is inside and not the centre.
fn polar_pair(mut uniform: impl FnMut() -> f64) -> (f64, f64, f64) {
    loop {
        let v1 = 2.0 * uniform() - 1.0;
        let v2 = 2.0 * uniform() - 1.0;
        let rsq = v1 * v1 + v2 * v2;
        if rsq < 1.0 && rsq != 0.0 {
            return (v1, v2, rsq);
        }
    }
}

const PARK_A: i32 = 16807;
const PARK_M: i32 = 2147483647;
const PARK_Q: i32 = 127773;
const PARK_R: i32 = 2836;

/// Park–Miller minimal standard generator (uniform in (0,1)), with Box–Muller gaussians.
#[derive(Debug, Clone)]
pub struct RanPark {
    state: i32,
    spare: Option<f64>,
}

impl RanPark {
    /// Seed the generator; seeds must be positive.
    pub fn new(seed: i32) -> Result<RanPark, String> {
        if seed <= 0 {
            return Err("Invalid seed for Park random # generator".into());
        }
        Ok(RanPark {
            state: seed,
            spare: None,
        })
    }

    /// Next uniform deviate in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        let k = self.state / PARK_Q;
        self.state = PARK_A * (self.state - k * PARK_Q) - PARK_R * k;
        if self.state < 0 {
            self.state += PARK_M;
        }
        self.state as f64 * (1.0 / PARK_M as f64)
    }

    /// Next standard normal deviate (mean 0, variance 1).
    pub fn gaussian(&mut self) -> f64 {
        if let Some(v) = self.spare.take() {
            return v;
        }
        let (v1, v2, rsq) = polar_pair(|| self.uniform());
        let fac = (-2.0 * rsq.ln() / rsq).sqrt();
        self.spare = Some(v1 * fac);
        v2 * fac
    }

    /// Restart the stream from a new positive seed.
    pub fn reset(&mut self, seed: i32) -> Result<(), String> {
        *self = RanPark::new(seed)?;
        Ok(())
    }

    /// Reseed from a base seed and a position (Jenkins one-at-a-time hash over the bytes of
    /// the seed and the three coordinates), then warm up with five draws.
    pub fn reset_at(&mut self, base: i32, coord: [f64; 3]) {
        let mut hash: u32 = 0;
        let mut mix = |byte: u8| {
            // the bytes are read as C `char`, which is signed here
            hash = hash.wrapping_add(byte as i8 as i32 as u32);
            hash = hash.wrapping_add(hash << 10);
            hash ^= hash >> 6;
        };
        base.to_le_bytes().into_iter().for_each(&mut mix);
        coord
            .iter()
            .flat_map(|c| c.to_le_bytes())
            .for_each(&mut mix);
        hash = hash.wrapping_add(hash << 3);
        hash ^= hash >> 11;
        hash = hash.wrapping_add(hash << 15);
        self.state = (hash & 0x7ffffff) as i32;
        if self.state == 0 {
            self.state = 1;
        }
        for _ in 0..5 {
            self.uniform();
        }
        self.spare = None;
    }

    /// The current internal state (the next seed).
    pub fn state(&self) -> i32 {
        self.state
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn park_miller_known_values() {
        // the minimal standard generator's published check: seed 1 gives 1043618065 after 10000 draws
        let mut r = RanPark::new(1).unwrap();
        for _ in 0..10000 {
            r.uniform();
        }
        assert_eq!(r.state(), 1043618065);
    }

    #[test]
    fn seeds() {
        assert!(RanMars::new(0).is_err());
        assert!(RanMars::new(900_000_001).is_err());
        assert!(RanPark::new(-5).is_err());
        assert!(check_seed(15485863).is_ok());
        assert!(check_seed(12345).is_err());
        assert!(check_seed(7).is_err());
    }

    #[test]
    fn mars_is_uniform_and_gaussian_moments() {
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
