//! What a run prepares before its first step: the pair model and its materials, the
//! neighbour cutoff's radii, growing radii and the fixes' resolved inputs.

use super::*;

impl Simulation {
    /// Build the contact models (pair and walls) from the current material properties.
    pub(super) fn init_pair(&mut self) -> Result<(), EngineError> {
        use crate::engine::granular;
        let input = self.material_input();
        self.init_pair_fix_styles(&input)?;
        // the rolling-friction models use a disc's inertia factor in 2d
        let two_d = self.dimension == 2;
        self.init_walls(&input)?;
        let Some(mut sel) = self.pair_selection.clone() else {
            self.pair = None;
            return Ok(());
        };
        if !self.pair_coeff_set {
            return Err("All pair coeffs are not set".into());
        }
        if !self.comm_vel {
            return Err("Pair granular requires ghost atoms store velocity".into());
        }
        sel.options.two_d = two_d;
        let frozen = fixes::frozen_groups(&self.fixes);
        self.pair = Some(if sel.surface == "multicontact" {
            granular::build_multicontact(&sel, &input, frozen, self.multicontact_input(&sel)?)?
        } else if sel.cohesion == crate::engine::wet::EASO {
            granular::build_wet(&sel, &input, frozen, &self.wet_input()?)?
        } else {
            granular::build(&sel, &input, frozen)?
        });
        Ok(())
    }

    /// Build the primitive and mesh walls' contact models; walls of `surface multicontact`
    /// get their stores of gathered contacts (kept across runs).
    fn init_walls(
        &mut self,
        input: &crate::engine::contact::MaterialInput,
    ) -> Result<(), EngineError> {
        use crate::engine::contact::multicontact::CONTACT_DISTANCE_FACTOR;
        use crate::engine::granular;
        // the rolling-friction models use a disc's inertia factor in 2d
        let two_d = self.dimension == 2;
        // LIGGGHTS's cutneighmax with the model's contact distance factor
        let cutneighmax =
            2.0 * self.largest_radius() * CONTACT_DISTANCE_FACTOR + self.neighbor.skin;
        let has_fix = self
            .fixes
            .iter()
            .any(|f| matches!(&f.kind, FixKind::Style(s) if s.multicontact_prefactor().is_some()));
        for k in 0..self.fixes.len() {
            let Some(selection) = self.fixes[k].kind.wall_selection() else {
                continue;
            };
            let (mut sel, multicontact) = (selection.clone(), selection.surface == "multicontact");
            if multicontact && !has_fix {
                return Err("No suitable multicontact fix found.".into());
            }
            sel.options.two_d = two_d;
            if let Some(wall) = self.fixes[k].kind.style_as_mut::<fixes::WallFix>() {
                let shape = (wall.wall_type, wall.plane, wall.shear);
                wall.model = Some(if multicontact {
                    granular::build_wall_multicontact(&sel, input, shape, cutneighmax)?
                } else {
                    granular::build_wall(&sel, input, shape.0, shape.1, shape.2)?
                });
                if multicontact && wall.multicontact.is_none() {
                    wall.multicontact = Some(granular::WallStore::new());
                }
                continue;
            }
            if let Some(wall) = self.fixes[k].kind.mesh_wall_mut() {
                let model = crate::engine::mesh_wall::build(&sel, input, cutneighmax)?;
                wall.model = Some(model);
                if multicontact && wall.multicontact.len() != wall.meshes.len() {
                    wall.multicontact = vec![granular::WallStore::new(); wall.meshes.len()];
                }
            }
        }
        Ok(())
    }

    /// What `fix multicontact/halfspace` gives `surface multicontact`: the first such fix's
    /// prefactor and group, with LIGGGHTS's error without one.
    fn multicontact_input(
        &self,
        sel: &crate::engine::contact::ModelSelection,
    ) -> Result<crate::engine::granular::MulticontactInput, EngineError> {
        if sel.cohesion == crate::engine::wet::EASO {
            return Err("pair_style gran surface multicontact with cohesion easo/capillary/viscous: not supported yet".into());
        }
        // pairs across periodic faces are seen from both sides there; this loop sees one
        if (0..3).any(|d| self.domain.periodic(d)) {
            return Err(
                "pair_style gran surface multicontact across periodic boundaries: not supported yet"
                    .into(),
            );
        }
        self.fixes
            .iter()
            .find_map(|f| match &f.kind {
                FixKind::Style(s) => s.multicontact_prefactor().map(|prefactor| {
                    crate::engine::granular::MulticontactInput {
                        prefactor,
                        group: f.group,
                    }
                }),
                _ => None,
            })
            .ok_or_else(|| "No suitable multicontact fix found.".into())
    }

    /// The material inputs from the `fix property/global` definitions (each present one,
    /// whether or not a model will ask for it).
    pub(crate) fn material_input(&self) -> crate::engine::contact::MaterialInput {
        let table = |name: &str| self.property(name).map(|(_, _, v)| v);
        let scalar = |name: &str| table(name).and_then(|v| v.first().copied());
        crate::engine::contact::MaterialInput {
            ntypes: self.ntypes as usize,
            units: self.units,
            soft_particles: self.soft_hard.0,
            hard_particles: self.soft_hard.1,
            allow_zero_restitution: self.zero_restitution,
            youngs_modulus: table("youngsModulus"),
            poissons_ratio: table("poissonsRatio"),
            coefficient_restitution: table("coefficientRestitution"),
            coefficient_friction: table("coefficientFriction"),
            coefficient_rolling_friction: table("coefficientRollingFriction"),
            coefficient_rolling_viscous_damping: table("coefficientRollingViscousDamping"),
            cohesion_energy_density: table("cohesionEnergyDensity"),
            characteristic_velocity: scalar("characteristicVelocity"),
            rolling_stiffness: scalar("rollingStiffness"),
            kn: table("kn"),
            kt: table("kt"),
            gamman: table("gamman"),
            gammat: table("gammat"),
            gamman_abs: table("gamman_abs"),
            gammat_abs: table("gammat_abs"),
            fluid_viscosity: table("FluidViscosity"),
            maximum_restitution: table("MaximumRestitution"),
            critical_stokes: table("CriticalStokes"),
            max_elastic_stiffness: table("coefficientMaxElasticStiffness"),
            adhesion_stiffness: table("coefficientAdhesionStiffness"),
            plasticity_depth: table("coefficientPlasticityDepth"),
        }
    }

    /// LIGGGHTS's `cutneighmax` at a run's init: twice the largest radius among the atoms
    /// and the particle distributions, times the pair style's contact distance factor, plus the
    /// skin (length).
    pub(crate) fn liggghts_cutneighmax(&self) -> f64 {
        2.0 * self.largest_radius() * self.contact_factor() + self.neighbor.skin
    }

    /// The largest radius among the atoms and the particle distributions (length), as
    /// LIGGGHTS's pair init counts future particles: by the fixes that report a largest
    /// radius (distributions and the insertions using them, a clump template's largest
    /// sphere); a template no distribution lists does not count.
    pub fn largest_radius(&self) -> f64 {
        let atoms = self.particles.radius.iter().copied().fold(0.0, f64::max);
        let distributions = self
            .fixes
            .iter()
            .filter_map(|f| f.kind.distribution())
            .map(|d| d.max_sphere_radius())
            .fold(0.0, f64::max);
        atoms.max(distributions)
    }

    /// A dry run's `run`: LIGGGHTS's init checks of particles, neighbour bins and mesh
    /// quality, no step; in a run's order: the init, the meshes' topology and quality
    /// checks of the setup, then the insertion fixes' setup (a stream's face must be planar,
    /// which its topology tells).
    pub fn check_run(&mut self) -> Result<(), EngineError> {
        self.check_run_init()?;
        self.build_mesh_topology()?;
        self.check_streams()?;
        self.check_stream_extrusions()?;
        for f in &self.fixes {
            if let Some(ins) = f.kind.insert_pack() {
                ins.check_tet_region(&self.regions, self.domain.lo, self.domain.hi)?;
            }
        }
        Ok(())
    }

    /// A fix changes particle radii during runs (`fix adapt ... atom diameter`).
    pub(super) fn radii_vary(&self) -> bool {
        self.fixes
            .iter()
            .any(|f| matches!(&f.kind, FixKind::Style(s) if s.changes_radii()))
    }

    pub(super) fn list_positions(&self) -> &[[f64; 3]] {
        self.list.built_positions()
    }

    /// Reshape the dynamic regions and evaluate the variables and regions the fixes read in
    /// this force evaluation (`fix setforce`/`addforce`).
    pub(super) fn resolve_force_fixes(
        &mut self,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let dynamic = self.regions.list.iter().any(|r| r.is_dynamic());
        let evaluating = self
            .fixes
            .iter()
            .any(|f| matches!(&f.kind, FixKind::Style(s) if s.evaluates()));
        if !dynamic && !evaluating {
            return Ok(());
        }
        // the particles stay put until the forcing fixes run: a variable read by several
        // fixes and regions here is evaluated once
        vars.hold(true);
        let result = self.reshape_and_evaluate(vars);
        vars.hold(false);
        result
    }

    fn reshape_and_evaluate(&mut self, vars: &mut dyn VariableSource) -> Result<(), EngineError> {
        if self.regions.list.iter().any(|r| r.is_dynamic()) {
            let mut regions = std::mem::take(&mut self.regions);
            let result = regions.reshape(Some(self.step), &mut |name| vars.equal(self, name));
            self.regions = regions;
            result?;
        }
        self.evaluate_fix_styles(vars)
    }

    /// Evaluate the variables of `fix move variable` for this step (before the moves).
    pub(super) fn resolve_move_fixes(
        &mut self,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        use crate::engine::fixes::ForceValue;
        for k in 0..self.fixes.len() {
            let values: Vec<ForceValue> = match self.fixes[k].kind.style_as::<fixes::Move>() {
                Some(fixes::Move {
                    motion: fixes::Motion::Variable { displace, velocity },
                    ..
                }) => displace.iter().chain(velocity.iter()).cloned().collect(),
                _ => continue,
            };
            let n = self.particles.len();
            let mut columns: Vec<Option<Vec<f64>>> = Vec::with_capacity(6);
            for v in &values {
                columns.push(match v {
                    ForceValue::Null => None,
                    ForceValue::Constant(c) => Some(vec![*c; n]),
                    ForceValue::Equal(name) => Some(vec![vars.equal(self, name)?; n]),
                    ForceValue::Atom(name) => Some(vars.atom(self, name)?),
                });
            }
            let resolved: Vec<[Option<f64>; 6]> = (0..n)
                .map(|i| std::array::from_fn(|c| columns[c].as_ref().map(|col| col[i])))
                .collect();
            if let Some(m) = self.fixes[k].kind.style_as_mut::<fixes::Move>() {
                m.resolved = resolved;
            }
        }
        Ok(())
    }
}
