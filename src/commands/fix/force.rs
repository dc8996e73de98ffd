//! `fix setforce` and `fix addforce`: prescribed force components (`post_force`), each a
//! number, `NULL` or a `v_name` equal- or atom-style variable evaluated every force
//! evaluation, optionally only inside a region.

use super::variable_value;
use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle, ForceValue, StepInputs};
use crate::engine::particles::Particles;

/// The declared signature of `fix setforce`.
pub const SETFORCE: Spec = style(
    "fix",
    "setforce",
    "fix ID GROUP setforce FX FY FZ",
    &[kw(
        "region",
        &[arg("R", Value::Id("region"))],
        "act only inside this region",
    )],
    "set force components (force, NULL to leave one)",
);

/// The declared signature of `fix addforce`.
pub const ADDFORCE: Spec = style(
    "fix",
    "addforce",
    "fix ID GROUP addforce FX FY FZ",
    &[kw(
        "region",
        &[arg("R", Value::Id("region"))],
        "act only inside this region",
    )],
    "add a force (or v_ variables) to every particle",
);

/// Whether the components replace the force or add to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// `setforce`: the component replaces the force's.
    Set,
    /// `addforce`: the component is added to the force.
    Add,
}

/// `fix setforce`/`addforce`: three components (force) and an optional region.
#[derive(Debug, Clone, PartialEq)]
pub struct Force {
    /// Set or add.
    pub action: Action,
    /// x, y, z components.
    pub values: [ForceValue; 3],
    /// `region ID`: only particles inside (region index).
    pub region: Option<usize>,
    /// Per-particle components of this force evaluation when variables or a region are
    /// involved (None: leave alone / add nothing), filled by [`FixStyle::evaluate`].
    pub resolved: Vec<[Option<f64>; 3]>,
}

impl Force {
    /// A fix with constant components (None: NULL) and no region.
    #[cfg(test)]
    pub fn constant(action: Action, values: [Option<f64>; 3]) -> Force {
        Force {
            action,
            values: values.map(|v| v.map_or(ForceValue::Null, ForceValue::Constant)),
            region: None,
            resolved: Vec::new(),
        }
    }

    /// Whether a component is a variable.
    fn has_variables(&self) -> bool {
        self.values
            .iter()
            .any(|v| matches!(v, ForceValue::Equal(_) | ForceValue::Atom(_)))
    }

    /// The constant components (None for NULL); only used without variables or region.
    fn constants(&self) -> [Option<f64>; 3] {
        self.values.clone().map(|v| match v {
            ForceValue::Constant(c) => Some(c),
            _ => None,
        })
    }
}

impl FixStyle for Force {
    fn name(&self) -> &str {
        match self.action {
            Action::Set => "setforce",
            Action::Add => "addforce",
        }
    }

    fn evaluates(&self) -> bool {
        self.region.is_some() || self.has_variables()
    }

    fn evaluate(
        &mut self,
        p: &Particles,
        _at: &FixStep,
        inputs: &mut dyn StepInputs,
    ) -> Result<(), EngineError> {
        let n = p.len();
        let mut columns: Vec<Option<Vec<f64>>> = Vec::with_capacity(3);
        for v in &self.values {
            columns.push(match v {
                ForceValue::Null => None,
                ForceValue::Constant(c) => Some(vec![*c; n]),
                ForceValue::Equal(name) => Some(vec![inputs.equal(name)?; n]),
                ForceValue::Atom(name) => Some(inputs.atom(name)?),
            });
        }
        let inside = self.region.map(|g| inputs.in_region_each(g, &p.x[..n]));
        let mut resolved = vec![[None; 3]; n];
        for (i, r) in resolved.iter_mut().enumerate() {
            if inside.as_ref().is_some_and(|inside| !inside[i]) {
                continue;
            }
            for d in 0..3 {
                r[d] = columns[d].as_ref().map(|c| c[i]);
            }
        }
        self.resolved = resolved;
        Ok(())
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        let constants = self.constants();
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            let v = if self.resolved.is_empty() {
                constants
            } else {
                self.resolved[i]
            };
            for d in 0..3 {
                if let Some(v) = v[d] {
                    match self.action {
                        Action::Set => p.f[i][d] = v,
                        Action::Add => p.f[i][d] += v,
                    }
                }
            }
        }
    }

    fn reads_computes(&self) -> bool {
        self.has_variables()
    }
}

/// `fix ID GROUP setforce|addforce FX FY FZ [region ID]` (force).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { style, .. } = *fix;
    a.count(
        6..=usize::MAX,
        &format!("fix ID GROUP {style} FX FY FZ [region ID]"),
    )?;
    let mut values = [ForceValue::Null, ForceValue::Null, ForceValue::Null];
    for (d, slot) in values.iter_mut().enumerate() {
        let w = a.word(3 + d)?;
        if let Some(name) = w.strip_prefix("v_") {
            *slot = variable_value(a, ctx, 3 + d, name, style)?;
        } else if w != "NULL" {
            *slot = ForceValue::Constant(a.real(3 + d)?);
        } else if style == "addforce" {
            return Err(a.error(3 + d, "Illegal fix addforce command"));
        }
    }
    let mut region = None;
    let mut i = 6;
    while i < a.len() {
        match a.word(i)? {
            "region" => {
                let id = a.word(i + 1)?;
                region = Some(ctx.sim.regions.find(id).ok_or_else(|| {
                    a.error(i + 1, format!("Region ID for fix {style} does not exist"))
                })?);
                i += 2;
            }
            w => {
                return Err(a.unsupported(i, &format!("fix {style} keyword {w}")));
            }
        }
    }
    let action = if style == "setforce" {
        Action::Set
    } else {
        Action::Add
    };
    Ok(Box::new(Force {
        action,
        values,
        region,
        resolved: Vec::new(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::domain::Domain;

    /// Inputs with one equal-style value, one atom-style column and a region x < 0.5.
    struct Fixed;

    impl StepInputs for Fixed {
        fn equal(&mut self, _name: &str) -> Result<f64, EngineError> {
            Ok(2.5)
        }
        fn atom(&mut self, _name: &str) -> Result<Vec<f64>, EngineError> {
            Ok(vec![1.0, -1.0])
        }
        fn in_region(&self, _region: usize, x: [f64; 3]) -> bool {
            x[0] < 0.5
        }
    }

    #[test]
    fn variables_and_region_resolve_per_particle() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0; 3], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.f = vec![[1.0; 3], [1.0; 3]];
        let domain = Domain::default();
        let at = FixStep::plain(1, 0, 1e-4, &domain);
        let mut set = Force {
            action: Action::Set,
            values: [
                ForceValue::Equal("e".into()),
                ForceValue::Null,
                ForceValue::Atom("a".into()),
            ],
            region: None,
            resolved: Vec::new(),
        };
        assert!(set.evaluates() && set.reads_computes());
        set.evaluate(&p, &at, &mut Fixed).unwrap();
        set.post_force(&mut p, &at);
        assert_eq!(p.f, vec![[2.5, 1.0, 1.0], [2.5, 1.0, -1.0]]);
        let mut add = Force::constant(Action::Add, [Some(0.5), None, None]);
        add.region = Some(0);
        assert!(add.evaluates() && !add.reads_computes());
        add.evaluate(&p, &at, &mut Fixed).unwrap();
        add.post_force(&mut p, &at);
        assert_eq!(p.f[0][0], 3.0);
        assert_eq!(p.f[1][0], 2.5);
        let mut plain = Force::constant(Action::Add, [Some(1.0), None, Some(2.0)]);
        assert!(!plain.evaluates());
        plain.post_force(&mut p, &at);
        assert_eq!(p.f[1], [3.5, 1.0, 1.0]);
    }
}
