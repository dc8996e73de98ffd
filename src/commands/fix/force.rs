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
    /// This force evaluation's components and region test when variables or a region are
    /// involved, filled by [`FixStyle::evaluate`] (kept between steps, so the step loop
    /// allocates nothing here); None: the constant components everywhere.
    pub evaluated: Option<Evaluated>,
}

/// One force evaluation of a [`Force`] with variables or a region.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Evaluated {
    /// x, y, z components (N).
    components: [Component; 3],
    /// Each particle is inside the region (None: no region).
    inside: Option<Vec<bool>>,
}

/// One component of a force evaluation (N).
#[derive(Debug, Clone, PartialEq, Default)]
enum Component {
    /// `NULL`: left alone.
    #[default]
    Null,
    /// The same value for every particle (a number or an equal-style variable).
    All(f64),
    /// One value per particle (an atom-style variable).
    Each(Vec<f64>),
}

impl Component {
    /// Particle `i`'s value (None: NULL).
    #[inline]
    fn at(&self, i: usize) -> Option<f64> {
        match self {
            Component::Null => None,
            Component::All(v) => Some(*v),
            Component::Each(c) => Some(c[i]),
        }
    }
}

impl Force {
    /// A fix with constant components (None: NULL) and no region.
    #[cfg(test)]
    pub fn constant(action: Action, values: [Option<f64>; 3]) -> Force {
        Force {
            action,
            values: values.map(|v| v.map_or(ForceValue::Null, ForceValue::Constant)),
            region: None,
            evaluated: None,
        }
    }

    /// Whether a component is a variable.
    fn has_variables(&self) -> bool {
        self.values
            .iter()
            .any(|v| matches!(v, ForceValue::Equal(_) | ForceValue::Atom(_)))
    }

    /// The constant components (NULL for any other); only used without variables or region.
    fn constants(&self) -> [Component; 3] {
        let constant = |v: &ForceValue| match v {
            ForceValue::Constant(c) => Component::All(*c),
            _ => Component::Null,
        };
        [
            constant(&self.values[0]),
            constant(&self.values[1]),
            constant(&self.values[2]),
        ]
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
        let mut e = self.evaluated.take().unwrap_or_default();
        for (v, c) in self.values.iter().zip(&mut e.components) {
            *c = match v {
                ForceValue::Null => Component::Null,
                ForceValue::Constant(v) => Component::All(*v),
                ForceValue::Equal(name) => Component::All(inputs.equal(name)?),
                ForceValue::Atom(name) => Component::Each(inputs.atom(name)?),
            };
        }
        e.inside = self.region.map(|g| inputs.in_region_each(g, &p.x[..n]));
        self.evaluated = Some(e);
        Ok(())
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        let constants;
        let (components, inside) = match &self.evaluated {
            Some(e) => (&e.components, e.inside.as_deref()),
            None => {
                constants = self.constants();
                (&constants, None)
            }
        };
        for i in 0..p.len() {
            if p.mask[i] & at.group == 0 || inside.is_some_and(|inside| !inside[i]) {
                continue;
            }
            for (d, c) in components.iter().enumerate() {
                if let Some(v) = c.at(i) {
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
        evaluated: None,
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
            evaluated: None,
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
