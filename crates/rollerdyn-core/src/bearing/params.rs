//! The model's immutable parameters, all SI, as the front end hands them over after
//! validating and deriving them from a configuration file: the physical parameters
//! ([`BearingParams`]) and, within them, the numerical settings ([`ModelOptions`]).

use super::topology::FLANGE_NAMES;
use crate::contact::border::BorderBands;
use crate::dynamics::rigid::TurningFrame;
use crate::error::{Error, Result};
use crate::geometry::end_flange::FlangeShape;
use crate::geometry::primitives::Vec3;
use crate::geometry::roller::RollerShape;
use crate::tribology::drag::Mixture;
use crate::tribology::friction::{BoundaryFriction, LoadSharing};
use crate::tribology::hydrodynamic::RigidFilm;
use crate::tribology::line_contact::LinePowerLaw;
use crate::tribology::squeeze::SqueezeFilm;
use crate::tribology::traction::EhlTraction;

/// A quantity over time: a ramp to a constant value, or a table (linear between rows,
/// constant outside).
#[derive(Debug, Clone, PartialEq)]
pub enum History {
    /// 0 before `start`, `value` after `end`; cosine or linear in between.
    Ramp {
        /// Final value.
        value: f64,
        /// Start of the ramp [s].
        start: f64,
        /// End of the ramp [s].
        end: f64,
        /// Cosine (C¹) rather than linear.
        cosine: bool,
    },
    /// Rows (t, value), t increasing.
    Table(Vec<(f64, f64)>),
}

impl History {
    /// A constant.
    pub fn constant(value: f64) -> Self {
        History::Ramp {
            value,
            start: 0.0,
            end: 0.0,
            cosine: false,
        }
    }

    /// (value, rate) at time t.
    pub fn at(&self, t: f64) -> (f64, f64) {
        match self {
            History::Ramp {
                value,
                start,
                end,
                cosine,
            } => {
                if t <= *start {
                    return (if end <= start { *value } else { 0.0 }, 0.0);
                }
                if t >= *end {
                    return (*value, 0.0);
                }
                let span = end - start;
                let x = (t - start) / span;
                if *cosine {
                    let arg = std::f64::consts::PI * x;
                    (
                        value * 0.5 * (1.0 - arg.cos()),
                        value * 0.5 * std::f64::consts::PI * arg.sin() / span,
                    )
                } else {
                    (value * x, value / span)
                }
            }
            History::Table(rows) => {
                let (first, last) = (rows[0], rows[rows.len() - 1]);
                if t <= first.0 {
                    return (first.1, 0.0);
                }
                if t >= last.0 {
                    return (last.1, 0.0);
                }
                let i = rows.partition_point(|r| r.0 <= t) - 1;
                let ((t0, v0), (t1, v1)) = (rows[i], rows[i + 1]);
                let rate = (v1 - v0) / (t1 - t0);
                (v0 + rate * (t - t0), rate)
            }
        }
    }

    /// ∫₀ᵗ of the history, t ≥ 0 (a constant before its first row and after its last, as
    /// [`Self::at`]): the angle a speed has turned through by t. Exact for both ramp shapes
    /// (the cosine's ½v[τ − (T/π) sin(πτ/T)] over the ramp's time τ and span T) and for a
    /// table's straight pieces (trapezoids).
    pub fn integral(&self, t: f64) -> f64 {
        match self {
            History::Ramp {
                value,
                start,
                end,
                cosine,
            } => {
                if end <= start {
                    return value * t.max(0.0);
                }
                let span = end - start;
                let tau = (t - start).clamp(0.0, span);
                let ramp = if *cosine {
                    let arg = std::f64::consts::PI * tau / span;
                    0.5 * value * (tau - span / std::f64::consts::PI * arg.sin())
                } else {
                    0.5 * value * tau * tau / span
                };
                ramp + value * (t - end).max(0.0)
            }
            History::Table(rows) => {
                let t = t.max(0.0);
                let (first, last) = (rows[0], rows[rows.len() - 1]);
                // the constant pieces before the first row and after the last
                let mut sum = first.1 * (t.min(first.0) - 0.0_f64.min(first.0)).max(0.0)
                    + last.1 * (t - last.0.max(0.0)).max(0.0);
                for w in rows.windows(2) {
                    let (a, b) = (w[0].0.max(0.0), w[1].0.min(t));
                    if b > a {
                        let (va, _) = self.at(a);
                        let (vb, _) = self.at(b);
                        sum += 0.5 * (va + vb) * (b - a);
                    }
                }
                sum
            }
        }
    }

    /// The least and the largest value the history takes (a ramp starts from 0).
    pub fn extremes(&self) -> (f64, f64) {
        match self {
            History::Ramp { value, .. } => (value.min(0.0), value.max(0.0)),
            History::Table(rows) => rows.iter().fold(
                (f64::INFINITY, f64::NEG_INFINITY),
                |(least, most), &(_, v)| (least.min(v), most.max(v)),
            ),
        }
    }

    fn check(&self, name: &str) -> Result<()> {
        match self {
            History::Ramp {
                value, start, end, ..
            } => {
                if !(value.is_finite() && start.is_finite() && end.is_finite()) || end < start {
                    return Err(Error::invalid(
                        name,
                        format!("ramp {start}..{end}"),
                        "finite, end >= start",
                    ));
                }
            }
            History::Table(rows) => {
                if rows.is_empty() || rows.windows(2).any(|w| w[1].0 <= w[0].0) {
                    return Err(Error::invalid(
                        name,
                        format!("{} rows", rows.len()),
                        "at least one row, times increasing",
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Which roller end–flange detector the run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Detector {
    /// Semi-analytical (Wolf et al. 2020), with conservative pruning (sect. 5.3).
    SemiAnalytical,
    /// Koch's gradient method, warm-started from the previous evaluation.
    Gradient,
    /// The mesh baseline (parry3d), at the given resolution.
    Mesh,
}

impl Detector {
    /// All three, in the order the configuration lists them.
    pub const ALL: [Detector; 3] = [Detector::SemiAnalytical, Detector::Gradient, Detector::Mesh];

    /// The detector's name in the configuration (`solver.detector`) and in results.
    pub fn name(&self) -> &'static str {
        match self {
            Detector::SemiAnalytical => "semi-analytical",
            Detector::Gradient => "gradient",
            Detector::Mesh => "mesh",
        }
    }
}

/// The friction data of one kind of contact surface pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePair {
    /// Composite roughness σ [m].
    pub roughness: f64,
    /// Zhou–Hoeprich load sharing (eq. 53).
    pub sharing: LoadSharing,
}

/// The planet carrier whose frame the bearing is simulated in (not in the paper): a planet
/// gear's bearing sits on a pin of a carrier that turns about the sun's axis, parallel to
/// the bearing's. The bodies' states are relative to the carrier, and the rollers feel the
/// carrier's inertial forces ([`crate::dynamics::rigid::TurningFrame`]); gravity turns
/// against the carrier. The rings' own inertial forces at the bearing's axis (the planet's
/// centrifugal force Ω_c²·offset) are part of the bearing's load; the inner ring's
/// displacement from that axis and its velocity feel the carrier's centrifugal, Coriolis
/// and Euler forces, and its tilt (when free) follows Euler's equations of its spin
/// relative to the carrier.
#[derive(Debug, Clone, PartialEq)]
pub struct Carrier {
    /// Carrier speed Ω_c [rad/s] about +x, over time (0: the bearing's frame is at rest).
    pub speed: History,
    /// The bearing's axis relative to the carrier's axis [m], across it (x = 0): the
    /// carrier's centrifugal field at the bearing is Ω_c²·offset.
    pub offset: Vec3,
}

impl Carrier {
    /// A carrier at rest: the bearing's frame is inertial.
    pub fn at_rest() -> Self {
        Self {
            speed: History::constant(0.0),
            offset: Vec3::zeros(),
        }
    }

    /// Whether the frame turns at any time.
    pub fn turns(&self) -> bool {
        self.speed.extremes() != (0.0, 0.0)
    }

    /// The carrier's frame at time t: Ω_c x̂, Ω̇_c x̂ and a point of its axis, −offset.
    pub fn frame(&self, t: f64) -> TurningFrame {
        let (speed, rate) = self.speed.at(t);
        TurningFrame {
            omega: Vec3::new(speed, 0.0, 0.0),
            omega_rate: Vec3::new(rate, 0.0, 0.0),
            axis_point: -self.offset,
        }
    }

    /// `gravity` (fixed in space, given as the carrier stands at t = 0) in the carrier's
    /// frame at time t: turned about x by −∫₀ᵗ Ω_c dt.
    pub fn gravity_at(&self, gravity: &Vec3, t: f64) -> Vec3 {
        if !self.turns() {
            return *gravity;
        }
        let (s, c) = (-self.speed.integral(t)).sin_cos();
        Vec3::new(
            gravity.x,
            c * gravity.y - s * gravity.z,
            s * gravity.y + c * gravity.z,
        )
    }
}

/// Everything the dynamic model needs.
#[derive(Debug, Clone)]
pub struct BearingParams {
    /// Number of rollers Z.
    pub roller_count: usize,
    /// Roller shape.
    pub roller: RollerShape,
    /// Slices per roller.
    pub slices: usize,
    /// Crown drop at the ends of the straight part [m] (0: straight profile).
    pub crown_drop: f64,
    /// Length of the crowned zone at each end [m].
    pub crown_length: f64,
    /// Relief k·D of the logarithmic profile [m] (0: none; see [`Self::crown_drop`]).
    pub log_relief: f64,
    /// Roller density [kg/m³].
    pub roller_density: f64,
    /// Inner raceway radius [m].
    pub inner_raceway_radius: f64,
    /// Outer raceway radius [m].
    pub outer_raceway_radius: f64,
    /// Inner ring flange shape (both sides).
    pub inner_flange: FlangeShape,
    /// Outer ring flange shape (both sides).
    pub outer_flange: FlangeShape,
    /// Which of the four flanges the rings have, in the order of [`FLANGE_NAMES`] (inner
    /// ring −x, +x, outer ring −x, +x): the paper's B1 has all four; a type NU bearing
    /// (ISO 15, DIN 5412-1) only the outer ring's two, a type NJ one of the inner ring's
    /// besides, an NF (full complement: NCF) the inner ring's two and one of the outer
    /// ring's. An absent flange has no contact ([`Self::check`] asks for a flange on each
    /// side of the rollers and for the two that carry the axial load).
    pub flanges: [bool; 4],
    /// Axial play per roller end and flange at the raceway, roller centred [m].
    pub inner_axial_play: f64,
    /// Same for the outer ring [m].
    pub outer_axial_play: f64,
    /// E' of roller–inner ring, roller–outer ring, roller–roller contacts [Pa].
    pub e_prime: [f64; 3],
    /// Eq. 11 for roller–inner race, roller–outer race, roller–roller.
    pub line_laws: [LinePowerLaw; 3],
    /// Inner ring mass [kg], axial and transverse inertia [kg m²].
    pub inner_ring_mass: f64,
    /// Inner ring axial inertia [kg m²].
    pub inner_ring_axial_inertia: f64,
    /// Inner ring transverse inertia [kg m²].
    pub inner_ring_transverse_inertia: f64,
    /// Inner ring tilt free (else locked).
    pub inner_ring_tilt_free: bool,
    /// Prescribed tilt (misalignment) of a locked inner ring about z, perpendicular to the
    /// radial load (−y) and the axial load (+x) as the paper's tilt (sect. 5.2) [rad]: the
    /// ring's axis is (cos γ, sin γ, 0) throughout the run. 0 unless the tilt is locked.
    pub inner_ring_misalignment: f64,
    /// EHL traction (sect. 3.2.1).
    pub traction: EhlTraction,
    /// Ambient viscosity η₀ [Pa s].
    pub eta0: f64,
    /// dη₀/dT [Pa s/K] (eq. 48).
    pub viscosity_slope: f64,
    /// α* [1/Pa].
    pub alpha_star: f64,
    /// Lubricant thermal conductivity [W/(m K)].
    pub thermal_conductivity: f64,
    /// Raceway, flange and roller–roller surfaces.
    pub raceway: SurfacePair,
    /// Roller end / flange surfaces.
    pub flange_surface: SurfacePair,
    /// The normal force law of the roller end–flange contacts ([`FlangeLaw`]).
    pub flange_law: FlangeLaw,
    /// Roller–roller surfaces.
    pub roller_roller: SurfacePair,
    /// Boundary friction (eqs. 51, 52).
    pub boundary: BoundaryFriction,
    /// Hysteresis coefficient α_v (eq. 55).
    pub hysteresis_coefficient: f64,
    /// How the rolling resistance (eqs. 55–57) acts on the two bodies of a contact
    /// ([`RollingResistance`]).
    pub rolling_resistance: RollingResistance,
    /// Damping ratio ζ of the normal contact damping [-].
    pub damping_ratio: f64,
    /// Gravity [m/s²] (B1: 9.81 m/s² along −y, a horizontal shaft).
    pub gravity: Vec3,
    /// The oil film in the roller–race and roller–roller gaps (not in the paper;
    /// [`crate::tribology::hydrodynamic`]).
    pub race_film: RigidFilm,
    /// The oil–air mixture whose drag acts on the rollers (not in the paper;
    /// [`crate::tribology::drag`]).
    pub mixture: Mixture,
    /// Radial load on the inner ring [N], along −y.
    pub radial_load: History,
    /// Axial load on the inner ring [N], along +x.
    pub axial_load: History,
    /// Inner ring speed [rad/s] about +x.
    pub inner_ring_speed: History,
    /// Outer ring speed [rad/s] about +x (not in the paper, whose outer ring is fixed; a
    /// planet gear turns its bearing's outer ring about a fixed pin).
    pub outer_ring_speed: History,
    /// The planet carrier the bearing turns with (not in the paper; [`Carrier`]).
    pub carrier: Carrier,
    /// Squeeze-film damping of the roller end–flange gaps (not in the paper;
    /// [`crate::tribology::squeeze`]).
    pub squeeze_film: SqueezeFilm,
    /// The numerical settings ([`ModelOptions`]).
    pub options: ModelOptions,
}

/// How the rolling resistance of a line contact (eqs. 55–57) acts on its two bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RollingResistance {
    /// The paper's: a pure moment against each body's rolling, the EHL part F_R·R with R
    /// the body's distance from the contact (eq. 56). The two moments do not cancel, so
    /// the contact does not conserve angular momentum (docs/dynamics.md, "Torque balance").
    /// B1's example configuration keeps it for the paper's study.
    Paper,
    /// Not in the paper, the default: in rolling the same moment about each body's own
    /// axis, and the force pair the oil film needs to be in force and moment equilibrium
    /// ([`crate::bearing::forces::rolling_resistance_balanced`]); the rolling force turned
    /// against the entrainment on both surfaces, as the pressure flow's shear is.
    #[default]
    Balanced,
}

impl RollingResistance {
    /// Both, in the order the configuration lists them.
    pub const ALL: [RollingResistance; 2] = [RollingResistance::Paper, RollingResistance::Balanced];

    /// The name in the configuration (`surfaces.rolling_resistance`).
    pub fn name(&self) -> &'static str {
        match self {
            RollingResistance::Paper => "paper",
            RollingResistance::Balanced => "balanced",
        }
    }
}

/// How a roller end–flange contact carries its load.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FlangeLaw {
    /// The paper's (sect. 2, 3.1.2): Hertz (Brewe–Hamrock) at the deepest point of the
    /// detected pairing.
    #[default]
    Point,
    /// Not in the paper: the whole overlap over the roller end
    /// ([`crate::contact::distributed`]) on a Winkler foundation
    /// ([`crate::tribology::foundation`]), for ends that lie nearly flat on the flange.
    Distributed,
}

impl FlangeLaw {
    /// Both, in the order the configuration lists them.
    pub const ALL: [FlangeLaw; 2] = [FlangeLaw::Point, FlangeLaw::Distributed];

    /// The law's name in the configuration (`surfaces.flange_law`).
    pub fn name(&self) -> &'static str {
        match self {
            FlangeLaw::Point => "point",
            FlangeLaw::Distributed => "distributed",
        }
    }
}

/// The model's numerical settings, apart from the physical parameters: how the roller
/// end–flange contacts are detected and blended, and whether friction acts. (The EHL
/// traction's choice between the integral and its table is made with the traction,
/// [`EhlTraction::tabulated`].)
#[derive(Debug, Clone, PartialEq)]
pub struct ModelOptions {
    /// Roller end–flange detector.
    pub detector: Detector,
    /// Mesh resolution (around, along) for [`Detector::Mesh`].
    pub mesh_resolution: (usize, usize),
    /// Skip pairings and flanges that cannot touch (semi-analytical only).
    pub pruning: bool,
    /// Half-widths of the bands over which the roller end–flange curvature is blended
    /// across patch borders ([`crate::contact::border`]).
    pub border_bands: BorderBands,
    /// Friction (tangential forces, rolling resistance) on; off only for checks.
    pub friction: bool,
}

impl BearingParams {
    /// Checks what the model relies on; the first violation is returned.
    pub fn check(&self) -> Result<()> {
        self.check_ring_tilt()?;
        self.check_fit()?;
        self.check_values()?;
        self.check_oil_and_gravity()?;
        self.radial_load.check("radial_load")?;
        self.axial_load.check("axial_load")?;
        self.inner_ring_speed.check("inner_ring_speed")?;
        self.outer_ring_speed.check("outer_ring_speed")?;
        self.carrier.speed.check("carrier_speed")?;
        self.check_carrier_offset()?;
        self.check_flanges()?;
        let (least, most) = self.axial_load.extremes();
        for axial_load in [least, most] {
            self.check_axial_load_path("axial_load", axial_load)?;
        }
        Ok(())
    }

    /// The carrier's offset: finite, across the axis (its x part would mean nothing: the
    /// carrier's axis is parallel to the bearing's).
    fn check_carrier_offset(&self) -> Result<()> {
        let o = &self.carrier.offset;
        if !(o.iter().all(|v| v.is_finite()) && o.x == 0.0) {
            return Err(Error::invalid(
                "carrier_offset",
                format!("{:?}", o.as_slice()),
                "finite, across the axis (x = 0): the carrier's axis is parallel to the bearing's",
            ));
        }
        Ok(())
    }

    /// A flange on each side of the rollers (−x: the inner or the outer ring's −x flange;
    /// +x likewise): without one the rollers have nothing to hold them along the axis.
    fn check_flanges(&self) -> Result<()> {
        for (side, name) in ["-x", "+x"].into_iter().enumerate() {
            if !(self.flanges[side] || self.flanges[side + 2]) {
                return Err(Error::invalid(
                    "flanges",
                    present_flanges(&self.flanges),
                    format!(
                        "the rollers need a flange on their {name} side (inner{name} or \
                         outer{name}): nothing else holds them along the axis"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The flanges an axial load on the inner ring presses ([`FLANGE_NAMES`]'s indices):
    /// along +x the inner ring's −x flange pushes the rollers onto the outer ring's +x
    /// flange; along −x the inner ring's +x flange onto the outer ring's −x flange.
    pub fn axial_load_flanges(axial_load: f64) -> [usize; 2] {
        if axial_load > 0.0 {
            [0, 3]
        } else {
            [1, 2]
        }
    }

    /// Refuses an axial load on the inner ring, together with the ring's weight along the
    /// axis, that one of the two flanges it presses ([`Self::axial_load_flanges`]) is not
    /// there to carry: nothing would hold the ring along the axis (`name`: the load's
    /// field).
    pub fn check_axial_load_path(&self, name: &str, axial_load: f64) -> Result<()> {
        let along_axis = axial_load + self.inner_ring_mass * self.gravity.x;
        if along_axis == 0.0 {
            return Ok(());
        }
        let path = Self::axial_load_flanges(along_axis);
        let Some(&missing) = path.iter().find(|&&k| !self.flanges[k]) else {
            return Ok(());
        };
        let weight = if self.gravity.x == 0.0 {
            String::new()
        } else {
            format!(
                " with the ring's weight along the axis ({} N)",
                self.inner_ring_mass * self.gravity.x
            )
        };
        Err(Error::invalid(
            name,
            format!("{axial_load} N"),
            format!(
                "pushes the inner ring along {}x{weight}, which only the flanges {} and {} \
                 carry, and the bearing has no {} flange (its flanges: {})",
                if along_axis > 0.0 { "+" } else { "-" },
                FLANGE_NAMES[path[0]],
                FLANGE_NAMES[path[1]],
                FLANGE_NAMES[missing],
                present_flanges(&self.flanges),
            ),
        ))
    }

    /// A prescribed misalignment within ±1°, and none with the tilt free.
    fn check_ring_tilt(&self) -> Result<()> {
        let gamma = self.inner_ring_misalignment;
        if !(gamma.is_finite() && gamma.abs() <= 1f64.to_radians()) {
            return Err(Error::invalid(
                "inner ring misalignment",
                gamma,
                "must be finite and within ±1° (±0.01745 rad)",
            ));
        }
        if self.inner_ring_tilt_free && gamma != 0.0 {
            return Err(Error::invalid(
                "inner ring misalignment",
                gamma,
                "must be 0 with the tilt free (a prescribed tilt needs the tilt locked)",
            ));
        }
        Ok(())
    }

    /// Rollers, slices and flanges that fit: at least three rollers and one slice, rollers
    /// between the raceways without overlapping each other, flanges lower than the roller
    /// and together lower than the annulus.
    fn check_fit(&self) -> Result<()> {
        if self.roller_count < 3 {
            return Err(Error::invalid("roller_count", self.roller_count, ">= 3"));
        }
        if self.slices == 0 {
            return Err(Error::invalid("slices", self.slices, ">= 1"));
        }
        let r = self.roller.radius;
        let gap = self.outer_raceway_radius - self.inner_raceway_radius - 2.0 * r;
        if gap.is_nan() || gap < 0.0 {
            return Err(Error::invalid(
                "roller diameter",
                2.0 * r,
                "rollers must fit between the raceways (no overlap at the start)",
            ));
        }
        // The flanges stand on the raceways and face each other across the annulus: each
        // must be lower than the roller, and together lower than the annulus (fuzzing found
        // NaN rates for flanges that overlap, docs/robustness.md, finding 3).
        for (name, flange) in [
            ("inner_flange.height", &self.inner_flange),
            ("outer_flange.height", &self.outer_flange),
        ] {
            let fits = flange.height < 2.0 * r;
            if !fits {
                return Err(Error::invalid(
                    name,
                    flange.height,
                    format!("must be < the roller diameter {:.6e} m", 2.0 * r),
                ));
            }
        }
        let annulus = self.outer_raceway_radius - self.inner_raceway_radius;
        let clear = self.inner_flange.height + self.outer_flange.height < annulus;
        if !clear {
            return Err(Error::invalid(
                "inner_flange.height + outer_flange.height",
                self.inner_flange.height + self.outer_flange.height,
                format!("must be < the annulus between the raceways {annulus:.6e} m"),
            ));
        }
        let pitch = 0.5 * (self.inner_raceway_radius + self.outer_raceway_radius);
        let chord = 2.0 * pitch * (std::f64::consts::PI / self.roller_count as f64).sin();
        if chord <= 2.0 * r {
            return Err(Error::invalid(
                "roller_count",
                self.roller_count,
                format!("neighbouring rollers overlap on the pitch circle (chord {chord:.6e} m <= roller diameter {:.6e} m)", 2.0 * r),
            ));
        }
        Ok(())
    }

    /// Masses, inertias, material values and settings positive (or non-negative) and
    /// finite.
    fn check_values(&self) -> Result<()> {
        for (name, v) in [
            ("roller_density", self.roller_density),
            ("inner_ring_mass", self.inner_ring_mass),
            ("inner_ring_axial_inertia", self.inner_ring_axial_inertia),
            (
                "inner_ring_transverse_inertia",
                self.inner_ring_transverse_inertia,
            ),
            ("eta0", self.eta0),
            ("thermal_conductivity", self.thermal_conductivity),
        ] {
            if !(v > 0.0 && v.is_finite()) {
                return Err(Error::invalid(name, v, "positive and finite"));
            }
        }
        for (name, v) in [
            ("border_band_roller", self.options.border_bands.roller_angle),
            (
                "border_band_flange",
                self.options.border_bands.flange_length,
            ),
            ("damping_ratio", self.damping_ratio),
            ("inner_axial_play", self.inner_axial_play),
            ("outer_axial_play", self.outer_axial_play),
            ("log_relief", self.log_relief),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(Error::invalid(name, v, "non-negative and finite"));
            }
        }
        if self.log_relief > 0.0 && self.crown_drop > 0.0 {
            return Err(Error::invalid(
                "log_relief",
                self.log_relief,
                "0 with a crown drop (a roller has one profile)",
            ));
        }
        Ok(())
    }

    /// The squeeze and race films' settings, gravity and the oil–air mixture.
    fn check_oil_and_gravity(&self) -> Result<()> {
        if self.squeeze_film.enabled {
            for (name, v) in [
                ("squeeze_film.half_width", self.squeeze_film.half_width),
                ("squeeze_film.floor", self.squeeze_film.floor),
                ("squeeze_film.cutoff", self.squeeze_film.cutoff),
            ] {
                if !(v > 0.0 && v.is_finite()) {
                    return Err(Error::invalid(name, v, "positive and finite"));
                }
            }
        }
        if !(self.gravity.iter().all(|g| g.is_finite()) && self.gravity.norm() <= 1e4) {
            return Err(Error::invalid(
                "gravity",
                format!("{:?}", self.gravity.as_slice()),
                "three finite accelerations, |g| <= 1e4 m/s^2",
            ));
        }
        if self.race_film.enabled
            && !(self.race_film.cutoff > 0.0 && self.race_film.cutoff.is_finite())
        {
            return Err(Error::invalid(
                "race_film.cutoff",
                self.race_film.cutoff,
                "positive and finite",
            ));
        }
        if !(self.race_film.suction_limit >= 0.0 && self.race_film.suction_limit.is_finite()) {
            return Err(Error::invalid(
                "race_film.suction_limit",
                self.race_film.suction_limit,
                "non-negative and finite",
            ));
        }
        for (name, v) in [
            ("mixture.density", self.mixture.density),
            ("mixture.viscosity", self.mixture.viscosity),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(Error::invalid(name, v, "non-negative and finite"));
            }
        }
        if self.mixture.density > 0.0 && self.mixture.viscosity <= 0.0 {
            return Err(Error::invalid(
                "mixture.viscosity",
                self.mixture.viscosity,
                "positive when the mixture has a density",
            ));
        }
        Ok(())
    }

    /// Crown drop of the roller profile at axial position s from the roller's centre,
    /// `straight` the length L_we of the generatrix between the edge tori (0 for a
    /// straight roller):
    /// - crowned: a circular-arc-like quadratic drop over `crown_length` at each end;
    /// - logarithmic (`log_relief` = k·D > 0): Lundberg's profile as ISO/TS 16281:2008
    ///   takes it for rollers whose profile is not known, k·D·ln[1 / (1 − (2s/L_we)²)]
    ///   (k = 0.00035 by default there). It grows without bound towards the generatrix's
    ///   ends; the slices' centres lie inside them (the outermost of 20 at 2s/L_we = 0.95:
    ///   2.33·k·D). At or beyond the ends it is infinite.
    pub fn crown_drop(&self, s: f64, straight: f64) -> f64 {
        if self.log_relief > 0.0 {
            let u = 2.0 * s / straight;
            return self.log_relief * -(1.0 - u * u).ln();
        }
        if self.crown_drop <= 0.0 || self.crown_length <= 0.0 {
            return 0.0;
        }
        let x = s.abs() - (0.5 * straight - self.crown_length);
        if x <= 0.0 {
            0.0
        } else {
            self.crown_drop * (x / self.crown_length).powi(2)
        }
    }
}

/// The flanges present, by name ("[inner-x, outer+x]").
fn present_flanges(flanges: &[bool; 4]) -> String {
    let names: Vec<&str> = (0..4)
        .filter(|&k| flanges[k])
        .map(|k| FLANGE_NAMES[k])
        .collect();
    format!("[{}]", names.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::test_b1::{params, B1};
    use proptest::prelude::*;

    /// ∫₀ᵗ of `h` by the composite trapezoidal rule on 200 000 intervals: the reference
    /// for [`History::integral`]. The integrand is piecewise smooth; at a kink of slope
    /// jump J the rule errs by at most J·(t/200 000)²/8, below 4e-8 of |v|max·t for the
    /// histories drawn below (ramps of at least 10 ms, rows at least 1 ms apart).
    fn trapezoids(h: &History, t: f64) -> f64 {
        let n = 200_000;
        let dt = t / n as f64;
        let inner: f64 = (1..n).map(|k| h.at(k as f64 * dt).0).sum();
        dt * (0.5 * (h.at(0.0).0 + h.at(t).0) + inner)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// The angle a carrier has turned through, `History::integral`, against the
        /// trapezoidal rule over `History::at`, for ramps of both shapes (and constants)
        /// and tables of up to five rows, some before t = 0; tolerance 1e-7 of |v|max·t.
        #[test]
        fn a_historys_integral_is_its_quadrature(
            value in -1000.0..1000.0f64,
            start in 0.0..0.3f64,
            // no span (a constant) or one much longer than the quadrature's intervals,
            // whose error at the ramp's kinks grows as interval² / span
            span in prop_oneof![Just(0.0), 0.01..0.3f64],
            cosine in any::<bool>(),
            rows in prop::collection::vec((-0.1..0.5f64, -1000.0..1000.0f64), 1..5),
            t in 0.01..0.8f64,
        ) {
            let ramp = History::Ramp { value, start, end: start + span, cosine };
            let mut rows = rows;
            rows.sort_by(|a, b| a.0.total_cmp(&b.0));
            rows.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-3);
            let table = History::Table(rows);
            for h in [ramp, table] {
                let (least, most) = h.extremes();
                let scale = least.abs().max(most.abs()).max(1e-3) * t;
                let (exact, quadrature) = (h.integral(t), trapezoids(&h, t));
                prop_assert!(
                    (exact - quadrature).abs() < 1e-7 * scale,
                    "{:?} to {}: {} against {}", h, t, exact, quadrature
                );
            }
        }
    }

    /// A bearing without a flange on one side of the rollers is refused by name, and so is
    /// an axial load (with the ring's weight along the axis) that one of its two flanges
    /// is not there to carry: along +x the inner ring's −x flange and the outer ring's +x
    /// flange (type NU has neither inner flange and carries none; NJ one inner flange, and
    /// carries its direction only).
    #[test]
    fn the_rollers_need_a_flange_each_side_and_an_axial_load_its_two() {
        let with = |flanges: [bool; 4], axial: f64, gravity_x: f64| {
            let mut p = params(&B1);
            p.flanges = flanges;
            p.axial_load = History::constant(axial);
            p.gravity.x = gravity_x;
            p.check().map_err(|e| e.to_string())
        };
        let nu = [false, false, true, true];
        let nj = [true, false, true, true];
        assert!(with([true; 4], 1000.0, 0.0).is_ok());
        assert!(with(nu, 0.0, 0.0).is_ok());
        assert!(with(nj, 1000.0, 0.0).is_ok());
        let e = with([true, false, true, false], 0.0, 0.0).unwrap_err();
        assert!(
            e.starts_with("flanges = [inner-x, outer-x]: the rollers need")
                && e.contains("+x side"),
            "{e}"
        );
        let e = with(nu, 1000.0, 0.0).unwrap_err();
        assert!(
            e.starts_with("axial_load = 1000 N") && e.contains("no inner-x flange"),
            "{e}"
        );
        let e = with(nj, -1.0, 0.0).unwrap_err();
        assert!(
            e.starts_with("axial_load = -1 N") && e.contains("no inner+x flange"),
            "{e}"
        );
        // a vertical shaft: the ring's weight (1 kg) along −x needs the inner ring's +x flange
        let e = with(nj, 0.0, -9.81).unwrap_err();
        assert!(
            e.contains("weight") && e.contains("no inner+x flange"),
            "{e}"
        );
        // a table that turns the load's direction needs all four
        let mut p = params(&B1);
        p.flanges = nj;
        p.axial_load = History::Table(vec![(0.0, 500.0), (1.0, -500.0)]);
        assert!(p
            .check()
            .unwrap_err()
            .to_string()
            .contains("no inner+x flange"));
    }

    /// Lundberg's logarithmic profile as ISO/TS 16281:2008 writes it: k·D·ln[1/(1 − u²)]
    /// with u = 2s/L_we; ln 2 · k·D where u² = 1/2, 0 at the centre, symmetric, growing
    /// towards the ends (2.33 k·D at B1's outermost slice centre, u = 0.95), and refused
    /// beside a crown drop or when negative.
    #[test]
    fn logarithmic_profile_is_lundbergs_relief() {
        let mut p = params(&B1);
        let (kd, length) = (0.00035 * 4.495e-3, 4.6e-3);
        p.log_relief = kd;
        assert_eq!(p.crown_drop(0.0, length), 0.0);
        let at_half = 0.5 * length * 0.5f64.sqrt();
        assert!((p.crown_drop(at_half, length) - kd * 2f64.ln()).abs() < 1e-15 * kd);
        let end = 0.95 * 0.5 * length;
        let expected = kd * (1.0 / (1.0 - 0.95f64 * 0.95)).ln();
        assert!((p.crown_drop(end, length) - expected).abs() < 1e-14 * expected);
        assert!((expected / kd - 2.3279).abs() < 1e-4);
        assert_eq!(p.crown_drop(-end, length), p.crown_drop(end, length));
        let mut previous = 0.0;
        for i in 1..100 {
            let drop = p.crown_drop(0.5 * length * i as f64 / 100.0, length);
            assert!(drop > previous, "{i}");
            previous = drop;
        }
        assert!(p.check().is_ok());
        p.crown_drop = 2e-6;
        p.crown_length = 1e-3;
        assert!(p.check().unwrap_err().to_string().starts_with("log_relief"));
        p.crown_drop = 0.0;
        p.log_relief = -1e-6;
        assert!(p.check().unwrap_err().to_string().starts_with("log_relief"));
    }

    #[test]
    fn cosine_ramp_is_c1_and_reaches_its_value() {
        let h = History::Ramp {
            value: 5000.0,
            start: 0.5,
            end: 0.7,
            cosine: true,
        };
        assert_eq!(h.at(0.2), (0.0, 0.0));
        assert_eq!(h.at(0.9), (5000.0, 0.0));
        assert!((h.at(0.6).0 - 2500.0).abs() < 1e-9);
        // Rate = d(value)/dt by central differences; zero rate at both ends (C¹).
        for t in [0.5001, 0.55, 0.6, 0.65, 0.6999] {
            let d = (h.at(t + 1e-7).0 - h.at(t - 1e-7).0) / 2e-7;
            assert!((d - h.at(t).1).abs() < 1e-4 * 5000.0 / 0.2, "{t}");
        }
        assert!(h.at(0.5 + 1e-9).1 < 1e-3 && h.at(0.7 - 1e-9).1 < 1e-3);
    }

    #[test]
    fn table_interpolates_linearly_and_holds_outside() {
        let h = History::Table(vec![(0.0, 0.0), (1.0, 10.0), (2.0, 10.0)]);
        assert_eq!(h.at(-1.0), (0.0, 0.0));
        assert_eq!(h.at(0.25), (2.5, 10.0));
        assert_eq!(h.at(1.5), (10.0, 0.0));
        assert_eq!(h.at(3.0), (10.0, 0.0));
        assert!(History::Table(vec![(1.0, 0.0), (0.5, 1.0)])
            .check("x")
            .is_err());
    }
}
