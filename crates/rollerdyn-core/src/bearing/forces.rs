//! Forces at one contact of the bearing: a line-contact slice (roller–race, roller–roller)
//! or a roller end–flange ellipse. Pure functions of the two bodies' kinematics and the
//! contact geometry; the model sums them.
//!
//! Conventions: body A and body B, the unit normal `n` points from A towards B, the
//! penetration δ > 0 is overlap, and the force on B is +F_n·n + F_t (A gets the
//! opposite). Surface speeds are taken relative to the moving contact location
//! (docs/dynamics.md, "Contacts"): u_i = tangential part of
//! (v_material,i − v_frame), sliding u_rel = u_B − u_A.

use super::params::RollingResistance;
use super::state::Kinematics;
use crate::geometry::primitives::Vec3;
use crate::numerics::smooth::{hyperbolic_ramp, smooth_max};
use crate::tribology::film::{FilmInputs, MoesTable, ThermalCorrection};
use crate::tribology::friction::{BoundaryFriction, LoadSharing};
use crate::tribology::hertz::{
    line_half_width, line_max_pressure, EllipticalContact, EllipticalMethod,
};
use crate::tribology::hydrodynamic::{film_line, RigidFilm};
use crate::tribology::line_contact::LinePowerLaw;
use crate::tribology::rolling_resistance::{ehl_rolling_force, hysteresis_moment};
use crate::tribology::traction::EhlTraction;

/// Smallest film used in the shear rate u_rel/h [m]: keeps the EHL traction finite where
/// the film vanishes (no entrainment); there the boundary share φ of eq. 53 is 1 anyway.
pub const FILM_FLOOR: f64 = 1e-9;

/// Regularisation of |u_rel| in the sliding direction u_rel/|u_rel| [m/s]; far below any
/// speed that matters (the traction is linear in u_rel there, so F_t·u_rel/|u_rel| is smooth).
const SLIP_FLOOR: f64 = 1e-12;

/// Relative width ε of the smooth lower bound of the damped normal force, see
/// [`damped_normal_force`].
const DAMPING_CLIP: f64 = 0.02;

/// What all contacts share: lubricant, friction and damping settings.
#[derive(Debug, Clone)]
pub struct Tribology {
    /// EHL traction.
    pub traction: EhlTraction,
    /// Boundary friction.
    pub boundary: BoundaryFriction,
    /// η₀ [Pa s].
    pub eta0: f64,
    /// α* [1/Pa].
    pub alpha_star: f64,
    /// The thermal correction of the lubricant (from dη₀/dT and λ_F).
    pub thermal: ThermalCorrection,
    /// Moes' line-contact film, tabulated (shared by clones).
    pub moes: std::sync::Arc<MoesTable>,
    /// α_v of eq. 55.
    pub hysteresis_coefficient: f64,
    /// How the rolling resistance acts on the two bodies.
    pub rolling_resistance: RollingResistance,
    /// Damping ratio ζ.
    pub damping_ratio: f64,
    /// Tangential forces and rolling resistance on (false: frictionless, for checks).
    pub friction: bool,
    /// The film of the line contacts across a gap ([`film_slice`]).
    pub film: RigidFilm,
}

impl Tribology {
    /// |u| regularised as sqrt(u² + v_s²) with the boundary-friction smoothing speed v_s:
    /// the film formulas (∝ u₀^0.5…0.7), the thermal correction (∝ u₀^0.46) and the
    /// rolling resistance have infinite slopes at u₀ = 0, which stall Newton's method
    /// where rollers start rolling; below v_s (1 mm/s for B1) the films are those of v_s.
    #[inline]
    pub fn regularised(&self, u: f64) -> f64 {
        let v = self.boundary.smoothing_speed;
        (u * u + v * v).sqrt()
    }

    /// The EHL traction's sliding speed and scale: F(u) = F_EHL(u_e)·u/u_e with
    /// u_e = sqrt(u² + v_s²). Above v_s this is the traction of sect. 3.2.1; below it the
    /// traction falls linearly to zero, as the boundary friction does (paper fig. 5). At GPa
    /// pressures the Carreau/limiting-shear-stress curve rises to its plateau within
    /// nanometres per second of sliding, a near-Coulomb switch that stalls any implicit
    /// integrator (docs/model.md, "Smoothing"); v_s (config
    /// `surfaces.boundary_friction.smoothing_speed`) sets the width of this creep zone.
    #[inline]
    pub fn creep(&self, sliding: f64) -> (f64, f64) {
        let effective = self.regularised(sliding);
        (effective, sliding / effective)
    }

    /// Thermal correction φ_th (eqs. 47, 48).
    #[inline]
    fn thermal(&self, u0: f64, sliding: f64) -> f64 {
        self.thermal.factor(u0, sliding)
    }

    fn film(&self, e_prime: f64) -> FilmInputs {
        FilmInputs {
            e_prime,
            alpha_star: self.alpha_star,
            eta0: self.eta0,
        }
    }
}

/// The elastic and surface data of one kind of line contact.
#[derive(Debug, Clone, Copy)]
pub struct LineKind {
    /// Eq. 11.
    pub law: LinePowerLaw,
    /// E' [Pa].
    pub e_prime: f64,
    /// Equivalent radius R' in the rolling direction [m].
    pub r_eff: f64,
    /// Roughness and load sharing.
    pub roughness: f64,
    /// Zhou–Hoeprich.
    pub sharing: LoadSharing,
    /// Film of counter-rotating surfaces: the greater of Moes and ZEV (roller–roller).
    pub counter_rotating: bool,
    /// Rolling resistance (race contacts only, sect. 3.3).
    pub rolling_resistance: bool,
    /// Mass moving against this contact, per unit slice length [kg/m] (for damping).
    pub mass_per_length: f64,
}

/// Forces of one contact.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForces {
    /// Normal force F_n ≥ 0 [N].
    pub normal: f64,
    /// Tangential force on B [N] (A gets the opposite).
    pub tangential: Vec3,
    /// Pure moment on A (rolling resistance) [N m].
    pub moment_a: Vec3,
    /// Pure moment on B (rolling resistance) [N m].
    pub moment_b: Vec3,
    /// Central film thickness h_c (thermally corrected) [m]; across a gap (the oil film of
    /// [`film_slice`]) the gap.
    pub film: f64,
    /// Maximum (Hertz) pressure p₀ of the section's contact [Pa]: eq. 17 for a slice, the
    /// ellipse's 3F/(2πab) at a flange; 0 across a gap.
    pub max_pressure: f64,
    /// Sliding speed |u_B − u_A| in the contact [m/s] (0 across a gap).
    pub sliding_speed: f64,
    /// Power the tangential force of sliding (traction, boundary friction, film shear)
    /// takes from the relative motion [W]: −F_t·(u_B − u_A) ≥ 0. Not the rolling
    /// resistance's forces and couples.
    pub sliding_power: f64,
    /// Power the normal force takes from the approach of the surfaces [W]: F_n·δ̇ (the
    /// elastic energy stored, the contact damping, the oil film's normal load).
    pub normal_power: f64,
}

impl ContactForces {
    /// Adds another contribution of the same contact (forces and moments; the film
    /// thickness stays this one's).
    #[inline]
    pub fn add(&mut self, other: &ContactForces) {
        self.normal += other.normal;
        self.tangential += other.tangential;
        self.moment_a += other.moment_a;
        self.moment_b += other.moment_b;
        self.sliding_power += other.sliding_power;
        self.normal_power += other.normal_power;
    }

    /// Total force on B.
    #[inline]
    pub fn force_on_b(&self, normal: &Vec3) -> Vec3 {
        self.normal * normal + self.tangential
    }
}

/// Normal force with contact damping: F_el + c·δ̇, with c = 2ζ·sqrt(k·m) for the local
/// stiffness k = dF_el/dδ and the mass m against the contact, bounded below by zero
/// smoothly: F = ½(F_d + sqrt(F_d² + (ε F_el)²)), F_d = F_el + c δ̇, ε = 0.02 (it adds at
/// most 1e-4·F_el at rest). The force is zero and continuous at zero penetration, since
/// both F_el and k vanish there, though not smooth: c ∝ sqrt(k) falls only as δ^0.25
/// (Hertz) or δ^0.056 (eq. 11), so an approaching contact meets its damping within
/// picometres. Hunt and Crossley's law, damping in proportion to F_el and smooth at first
/// touch, took more steps on B1 (docs/performance-log.md, "The figures again, profile-guided
/// optimisation, and Hunt–Crossley damping").
#[inline]
pub fn damped_normal_force(elastic: f64, stiffness: f64, mass: f64, zeta: f64, rate: f64) -> f64 {
    if elastic <= 0.0 {
        return 0.0;
    }
    let damped = elastic + 2.0 * zeta * (stiffness * mass).sqrt() * rate;
    hyperbolic_ramp(damped, DAMPING_CLIP * elastic)
}

/// Surface speeds of A and B relative to the contact frame, in the tangent plane.
#[inline]
fn tangential_speeds(
    a: &Kinematics,
    b: &Kinematics,
    p: &Vec3,
    n: &Vec3,
    frame: &Vec3,
) -> (Vec3, Vec3, f64) {
    let va = a.point_velocity(p);
    let vb = b.point_velocity(p);
    let rate = -(vb - va).dot(n);
    debug_assert!(rate.is_nan() || rate == penetration_rate(a, b, p, n));
    let ua = va - frame;
    let ub = vb - frame;
    (ua - ua.dot(n) * n, ub - ub.dot(n) * n, rate)
}

/// Rate of penetration δ̇ = −(v_B − v_A)·n of the material points of A and B at `p`
/// (positive while the bodies approach).
#[inline]
pub fn penetration_rate(a: &Kinematics, b: &Kinematics, p: &Vec3, n: &Vec3) -> f64 {
    -(b.point_velocity(p) - a.point_velocity(p)).dot(n)
}

/// Direction of the rolling-resistance moment on a body whose surface moves along
/// `rolling` at `p`: the axis d with d × (p − c) along `rolling`.
#[inline]
fn rolling_axis(body: &Kinematics, p: &Vec3, rolling: &Vec3) -> Vec3 {
    (p - body.center).cross(rolling).normalize()
}

/// One section of a line contact as its force laws see it: a slice ([`line_slice`]) or a
/// point of the oil film ([`film_slice`]).
#[derive(Debug, Clone, Copy)]
pub struct Section<'a> {
    /// Body A (a ring, or roller i of a pair).
    pub a: &'a Kinematics,
    /// Body B (roller i, or roller i+1 of a pair).
    pub b: &'a Kinematics,
    /// Unit normal from A to B.
    pub normal: Vec3,
    /// Contact location P_m [m].
    pub location: Vec3,
    /// Penetration δ (negative: a gap) [m].
    pub penetration: f64,
    /// Length of the contact the section stands for [m].
    pub length: f64,
    /// Unit rolling direction (n × roller axis).
    pub rolling: Vec3,
    /// Velocity of the contact location [m/s].
    pub frame: Vec3,
}

impl Section<'_> {
    /// Surface speeds of A and B relative to the contact frame in the tangent plane, and
    /// the rate of penetration.
    #[inline]
    fn speeds(&self) -> (Vec3, Vec3, f64) {
        tangential_speeds(self.a, self.b, &self.location, &self.normal, &self.frame)
    }

    /// Rolling resistance of both bodies (surface speeds `u` along the rolling
    /// direction): the hysteresis couple `m_b` (eq. 55) and the EHL rolling force `f_r`
    /// (eqs. 56, 57) per body, mixed by the boundary `share` (eqs. 53, 54); applied as the
    /// paper does or balanced ([`RollingResistance`]).
    ///
    /// The paper's switches each body's moment smoothly with that body's direction of
    /// rolling (tanh(u/v_s)). The balanced law turns the rolling force against the
    /// entrainment, tanh(u_m/v_s) with u_m = (u_A + u_B)/2, on both surfaces: it is the
    /// shear of the pressure flow, −(h/2)·∂p/∂x on each surface alike (from the velocity
    /// profile behind the Reynolds equation: Hamrock, Schmid & Jacobson, Fundamentals of
    /// Fluid Film Lubrication, 2nd ed. 2004, the chapter on the Reynolds equation), and the
    /// pressure is built by the entrainment.
    /// In rolling the two agree; a roller that skids on a turning race (u_B = 0) still
    /// feels it, and counter-rotating neighbours (u_m = 0) do not. The hysteresis couple
    /// stays with B's own rolling (its material's passage through the contact).
    #[inline]
    fn rolling_resistance(
        &self,
        out: &mut ContactForces,
        tri: &Tribology,
        (ua, ub): (f64, f64),
        share: f64,
        (m_b, f_r): (f64, f64),
    ) {
        let v_s = tri.boundary.smoothing_speed;
        if tri.rolling_resistance == RollingResistance::Paper {
            // A moment against each body's rolling, of size m_b + F_R·|P − c|: the moment
            // about c of a surface force F_R at P, without the force.
            for (body, u, moment) in [
                (self.a, ua, &mut out.moment_a),
                (self.b, ub, &mut out.moment_b),
            ] {
                let arm = (self.location - body.center).norm();
                let axis = rolling_axis(body, &self.location, &self.rolling);
                let size = LoadSharing::mix_by_share(share, m_b, f_r * arm);
                *moment = -(size * (u / v_s).tanh()) * axis;
            }
            return;
        }
        let pressure_flow_shear = (1.0 - share) * f_r * (0.5 * (ua + ub) / v_s).tanh();
        let reaction = rolling_resistance_balanced(
            self,
            share * m_b * (ub / v_s).tanh(),
            pressure_flow_shear,
            pressure_flow_shear,
        );
        out.tangential += reaction.tangential;
        out.moment_a = reaction.moment_a;
        out.moment_b = reaction.moment_b;
    }
}

/// Rolling resistance of a line-contact section that conserves momentum and angular
/// momentum (not in the paper; docs/dynamics.md, "Torque balance"): the paper's resisting
/// moments about each body's own axis, completed by the forces the oil film must exert to
/// be in equilibrium.
///
/// * EHL (eq. 56): the inlet's shear acts on the surfaces with F_A and F_B (signed along
///   the rolling direction t) at P; the model passes F_A = F_B, the pressure flow's shear
///   against the entrainment ([`Section`]'s rolling resistance). The film's pressure acts normal to each
///   cylinder, so its tangential resultants g_A, g_B pass through the bodies' axes, at
///   Q_A = P − ρ_A n and Q_B = P + ρ_B n (ρ the signed distances from P to the axes along
///   the normal n from A to B; negative for a concave outer raceway). A massless film in
///   equilibrium needs g_A + g_B = F_A + F_B (forces) and ρ_A g_A = ρ_B g_B (moments about
///   P), so g_B = (F_A + F_B)·ρ_A/(ρ_A + ρ_B). On B: −F_B t at P and g_B t at Q_B, that is
///   the force (g_B − F_B) t at P and the couple ρ_B g_B (n × t); on A the opposite force
///   and couple. About its own axis each body then feels F·ρ (against its rolling when the
///   surfaces roll together, as in the paper), and the pair exerts no net force or moment.
/// * Hysteresis (eq. 55): the normal force shifted along t towards the inlet, a collinear
///   pair, so a couple of size m_b about n × t (B's rolling axis) against B's rolling, and
///   its opposite on A, for every slice. (The paper's form turns each body's couple about
///   the axis of its [`rolling_axis`], which tilts for slices away from the body's centre:
///   on B1's roller the component about its axis is ρ/sqrt(ρ² + s²) of it for a slice at
///   s: 24 % less at the outermost slices, 10 % less on average over the 20.)
///
/// `hysteresis` = m_b·tanh(u_B/v_s) (the boundary share included), `f_a`, `f_b` the shear
/// on each surface along t (the model passes F_R·tanh(u_m/v_s) for both, u_m the
/// entrainment speed). Returns the force on B (A gets the opposite) and the couples.
pub fn rolling_resistance_balanced(
    section: &Section,
    hysteresis: f64,
    f_a: f64,
    f_b: f64,
) -> ContactForces {
    let (n, t, p) = (&section.normal, &section.rolling, &section.location);
    // The vector from P to the nearest point of a body's axis.
    let to_axis = |body: &Kinematics| {
        let c = body.center - p;
        c - c.dot(&body.axis) * body.axis
    };
    let (rho_a, rho_b) = (-to_axis(section.a).dot(n), to_axis(section.b).dot(n));
    let g_b = (f_a + f_b) * rho_a / (rho_a + rho_b);
    // n × t = −a_B for t = n × a_B: against B's spin, whose sign is that of u_B (ρ_B > 0).
    let hysteresis_couple = hysteresis * n.cross(t);
    let couple = rho_b * g_b * n.cross(t) + hysteresis_couple;
    ContactForces {
        tangential: (g_b - f_b) * t,
        moment_a: -couple,
        moment_b: couple,
        ..Default::default()
    }
}

/// One slice of a line contact (paper sect. 3.1.3, 3.2, 3.3): normal force by eq. 11 with
/// damping, film by Moes (eqs. 33–38, from the table [`MoesTable`]; for counter-rotating
/// surfaces the greater of Moes and ZEV, eqs. 39–44) with the thermal correction (eq. 47),
/// EHL traction (sect. 3.2.1),
/// boundary friction (eqs. 51, 52), mixed by eqs. 53, 54, and for race contacts rolling
/// resistance (eqs. 55–57): as pure moments against both bodies' rolling (the paper's) or
/// against the entrainment, balanced by the film's force pair ([`RollingResistance`]).
///
pub fn line_slice(tri: &Tribology, kind: &LineKind, section: &Section) -> ContactForces {
    let Section {
        penetration,
        length,
        rolling,
        ..
    } = *section;
    if penetration <= 0.0 {
        return ContactForces::default();
    }
    let elastic = kind.law.force(penetration, length);
    let stiffness = elastic / (kind.law.k2 * penetration);
    let (ua, ub, approach) = section.speeds();
    let f_n = damped_normal_force(
        elastic,
        stiffness,
        kind.mass_per_length * length,
        tri.damping_ratio,
        approach,
    );
    let half_width = line_half_width(f_n, length, kind.r_eff, kind.e_prime);
    let p0 = line_max_pressure(f_n, half_width, length);
    if !tri.friction {
        return ContactForces {
            normal: f_n,
            normal_power: f_n * approach,
            max_pressure: p0,
            sliding_speed: (ub - ua).norm(),
            ..Default::default()
        };
    }
    let (ua_r, ub_r) = (ua.dot(&rolling), ub.dot(&rolling));
    let slip = ub - ua;
    let slip_squared = slip.norm_squared();
    let slip_norm = (slip_squared + SLIP_FLOOR * SLIP_FLOOR).sqrt();
    let u0 = tri.regularised(0.5 * (ua_r + ub_r));
    let q = f_n / length;
    let film = tri.film(kind.e_prime);
    let moes = film.moes_line_tabulated(&tri.moes, kind.r_eff, u0, q);
    let isothermal = if kind.counter_rotating {
        let zev = 0.5 * (tri.regularised(ua_r) + tri.regularised(ub_r));
        smooth_max(moes, film.zev_line(kind.r_eff, zev, q))
    } else {
        moes
    };
    let phi_th = tri.thermal(u0, slip_norm);
    let h = isothermal * phi_th;
    let (rate, scale) = tri.creep(slip_norm);
    let fluid = scale
        * tri
            .traction
            .line_force(p0, half_width, length, rate, h + FILM_FLOOR);
    let boundary = tri.boundary.force(f_n, slip_norm, u0);
    let share = kind.sharing.boundary_share(h / kind.roughness);
    let f_t = LoadSharing::mix_by_share(share, boundary, fluid);
    let mut out = ContactForces {
        normal: f_n,
        tangential: -(f_t / slip_norm) * slip,
        film: h,
        max_pressure: p0,
        sliding_speed: slip_squared.sqrt(),
        sliding_power: f_t / slip_norm * slip_squared,
        normal_power: f_n * approach,
        ..Default::default()
    };
    if kind.rolling_resistance {
        let m_b = hysteresis_moment(tri.hysteresis_coefficient, f_n, half_width);
        let f_r = ehl_rolling_force(kind.e_prime, kind.r_eff, length, tri.eta0, u0, f_n) * phi_th;
        section.rolling_resistance(&mut out, tri, (ua_r, ub_r), share, (m_b, f_r));
    }
    out
}

/// The oil film of one slice of a line contact across a gap or within the first δ_f of
/// penetration ([`crate::tribology::hydrodynamic`], [`RigidFilm::contact_fade`]: σ, or
/// longer where the film at contact carries more than the elastic law over σ; not in the
/// paper): Martin's load with
/// the squeeze term, bounded below by zero (cavitation), along the normal; Couette shear
/// against the sliding; and the film's rolling force, applied as the EHL rolling resistance
/// of [`line_slice`] is (the paper's law: against both bodies' rolling; the balanced one:
/// against the entrainment; [`RollingResistance`]).
/// The mean surface speed is regularised as the EHL film's ([`Tribology::regularised`]).
/// Zero where the film does not act ([`RigidFilm::gap_and_weight`]).
pub fn film_slice(tri: &Tribology, kind: &LineKind, section: &Section) -> ContactForces {
    let Section {
        penetration,
        length,
        rolling,
        ..
    } = *section;
    let sigma = kind.roughness;
    if !tri.film.reaches(penetration) {
        return ContactForces::default();
    }
    let (ua, ub, rate) = section.speeds();
    let (ua_r, ub_r) = (ua.dot(&rolling), ub.dot(&rolling));
    let u_m = tri.regularised(0.5 * (ua_r + ub_r));
    let film_at = |h: f64| film_line(tri.eta0, kind.r_eff, h, u_m, rate, tri.film.suction_limit);
    // In contact the film's gap is σ: its load there sets how far it fades.
    let (fade, at_contact) = if penetration > 0.0 {
        let film = film_at(sigma);
        let deflection = |q: f64| kind.law.deflection(q, 1.0);
        (
            RigidFilm::contact_fade(sigma, film.load, deflection),
            Some(film),
        )
    } else {
        (sigma, None)
    };
    let Some((gap, weight)) = tri.film.gap_and_weight(penetration, sigma, fade) else {
        return ContactForces::default();
    };
    let film = at_contact.unwrap_or_else(|| film_at(gap));
    let scale = weight * length;
    let mut out = ContactForces {
        normal: scale * film.load,
        film: gap,
        normal_power: scale * film.load * rate,
        ..Default::default()
    };
    if !tri.friction {
        return out;
    }
    out.tangential = -(scale * film.shear) * (ub - ua);
    out.sliding_power = scale * film.shear * (ub - ua).norm_squared();
    section.rolling_resistance(
        &mut out,
        tri,
        (ua_r, ub_r),
        0.0,
        (0.0, scale * film.rolling),
    );
    out
}

/// The data of the roller end–flange contacts.
#[derive(Debug, Clone, Copy)]
pub struct EllipseKind {
    /// E' [Pa].
    pub e_prime: f64,
    /// Roughness [m].
    pub roughness: f64,
    /// Zhou–Hoeprich.
    pub sharing: LoadSharing,
    /// Mass against the contact [kg] (for damping).
    pub mass: f64,
}

/// A roller end–flange contact (sect. 3.1.2, 3.2): Hertz with Brewe–Hamrock (eqs. 5–8)
/// and damping, Chittenden's film (eqs. 45, 46) for the entrainment angle ξ measured from
/// the ellipse's major axis, EHL, boundary and mixed friction; no rolling resistance.
/// A is the ring (flange), B the roller; `normal` from the flange to the roller.
#[allow(clippy::too_many_arguments)]
pub fn end_flange(
    tri: &Tribology,
    kind: &EllipseKind,
    ring: &Kinematics,
    roller: &Kinematics,
    normal: &Vec3,
    location: &Vec3,
    penetration: f64,
    radii: (f64, f64),
    major_axis: &Vec3,
    frame: &Vec3,
) -> ContactForces {
    // Radii outside (0, ∞) never come from the detectors (contact::relative_radius); NaN
    // (no curvature) carries no load.
    if penetration <= 0.0 || !(radii.0 > 0.0 && radii.1 > 0.0 && radii.0.max(radii.1).is_finite()) {
        return ContactForces::default();
    }
    let hertz = EllipticalContact::new(
        radii.0,
        radii.1,
        kind.e_prime,
        EllipticalMethod::BreweHamrock,
    );
    let elastic = hertz.force(penetration);
    let load = FlangeLoad {
        elastic,
        stiffness: 1.5 * elastic / penetration,
        radii: (hertz.rx, hertz.ry),
        major_axis: *major_axis,
    };
    flange_friction(
        tri,
        kind,
        ring,
        roller,
        normal,
        location,
        &load,
        frame,
        |f| {
            let e = hertz.at_force(f);
            (e.max_pressure, e.semi_major, e.semi_minor)
        },
    )
}

/// The elastic load of a roller end–flange contact and the shape its film and traction
/// see: relative radii R_x ≤ R_y and the direction of the major axis (along R_y).
#[derive(Debug, Clone, Copy)]
pub struct FlangeLoad {
    /// Elastic normal force [N].
    pub elastic: f64,
    /// dF/dδ for the damping [N/m].
    pub stiffness: f64,
    /// (R_x, R_y) [m].
    pub radii: (f64, f64),
    /// Unit major axis.
    pub major_axis: Vec3,
}

/// A roller end–flange contact of the given elastic `load` (Hertz's, [`end_flange`], or
/// the distributed overlap's, [`crate::tribology::foundation`]): damping, Chittenden's
/// film (eqs. 45, 46), EHL traction over the ellipse `ellipse(F_N)` = (p₀, a, b),
/// boundary and mixed friction (sect. 3.2).
#[allow(clippy::too_many_arguments)]
pub fn flange_friction(
    tri: &Tribology,
    kind: &EllipseKind,
    ring: &Kinematics,
    roller: &Kinematics,
    normal: &Vec3,
    location: &Vec3,
    load: &FlangeLoad,
    frame: &Vec3,
    ellipse: impl Fn(f64) -> (f64, f64, f64),
) -> ContactForces {
    let (ua, ub, approach) = tangential_speeds(ring, roller, location, normal, frame);
    let f_n = damped_normal_force(
        load.elastic,
        load.stiffness,
        kind.mass,
        tri.damping_ratio,
        approach,
    );
    let (max_pressure, semi_major, semi_minor) = ellipse(f_n);
    let slip = ub - ua;
    if !tri.friction {
        return ContactForces {
            normal: f_n,
            normal_power: f_n * approach,
            max_pressure,
            sliding_speed: slip.norm(),
            ..Default::default()
        };
    }
    let slip_squared = slip.norm_squared();
    let slip_norm = (slip_squared + SLIP_FLOOR * SLIP_FLOOR).sqrt();
    let entrainment = 0.5 * (ua + ub);
    let u0 = tri.regularised(entrainment.norm());
    // ξ from the major axis; only cos²ξ = (u₀·m)²/u₀² enters eq. 45, smooth in u₀ (u₀ is
    // regularised, so never below |u₀·m|).
    let along = entrainment.dot(&load.major_axis);
    let cos2_xi = (along * along / (u0 * u0)).min(1.0);
    let film = tri.film(kind.e_prime);
    let phi_th = tri.thermal(u0, slip_norm);
    let h = film.chittenden_at(load.radii.0, load.radii.1, cos2_xi, u0, f_n) * phi_th;
    let (rate, scale) = tri.creep(slip_norm);
    let fluid = scale
        * tri
            .traction
            .ellipse_force(max_pressure, semi_major, semi_minor, rate, h + FILM_FLOOR);
    let boundary = tri.boundary.force(f_n, slip_norm, u0);
    let f_t = kind.sharing.mix(h / kind.roughness, boundary, fluid);
    ContactForces {
        normal: f_n,
        tangential: -(f_t / slip_norm) * slip,
        film: h,
        max_pressure,
        sliding_speed: slip_squared.sqrt(),
        sliding_power: f_t / slip_norm * slip_squared,
        normal_power: f_n * approach,
        ..Default::default()
    }
}

#[cfg(test)]
impl Tribology {
    /// The fuzz target's tribology (B1's data, η₀ = 16.5 mPa s), friction on.
    pub(crate) fn b1_for_tests() -> Tribology {
        use crate::tribology::lubricant::{Carreau, Roelands};
        use crate::tribology::traction::LimitingShearStress;
        let eta0 = 0.0165;
        Tribology {
            traction: EhlTraction::new(
                Roelands {
                    eta_p: 0.0631e-3,
                    p_p: -196e6,
                    z: 0.62,
                },
                Carreau { tau0: 5e6, n: 0.5 },
                LimitingShearStress {
                    chi: 0.0,
                    p_star: 1.0,
                    tau_l0: 3e7,
                    smoothing: 20e6,
                },
                eta0,
                12,
            ),
            boundary: BoundaryFriction {
                mu_b0: 0.1,
                s0: 0.1,
                smoothing_speed: 1e-3,
            },
            eta0,
            alpha_star: 2e-8,
            thermal: ThermalCorrection::new(-1e-3 * eta0, 0.134),
            moes: Default::default(),
            hysteresis_coefficient: 0.01,
            rolling_resistance: RollingResistance::Paper,
            damping_ratio: 0.1,
            friction: true,
            film: RigidFilm {
                enabled: true,
                cutoff: 100e-6,
                suction_limit: 1e5,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn tribology() -> Tribology {
        Tribology::b1_for_tests()
    }

    /// Finding 5 of docs/robustness.md: with friction on, an overlap of 17 mm on a
    /// contact of R_x = 0.1 mm (a 0.5 mm roller on a 0.5 m ring tilted 2°, as the fuzzer
    /// found) gave a NaN tangential force (the film's Roelands viscosity overflowed at
    /// p₀ ~ 1e12 Pa, and Carreau made ∞·0 = NaN of it). Every force stays finite for any
    /// overlap, curvature and speed, and the friction force stays below μ_B·F_n + the
    /// area times the limiting shear stress.
    #[test]
    fn end_flange_forces_stay_finite_at_huge_overlaps() {
        let tri = tribology();
        let kind = EllipseKind {
            e_prime: 2.3e11,
            roughness: 0.1e-6,
            sharing: LoadSharing { b: 1.5, c: 1.2 },
            mass: 1e-3,
        };
        let p = Vec3::new(0.0, 0.5, 0.0);
        for spin in [0.0, 1.0, 300.0] {
            let ring = Kinematics {
                omega: Vec3::new(spin / 3.0, 0.0, 0.0),
                ..Kinematics::fixed()
            };
            let roller = Kinematics {
                center: p,
                axis: Vec3::x(),
                velocity: Vec3::new(0.0, 0.0, spin / 30.0),
                omega: Vec3::new(-spin, 0.0, 0.0),
            };
            for penetration in [1e-9, 1e-6, 1e-3, 17e-3, 20e-3, 0.1, 1.0] {
                for (rx, ry) in [(1e-4, 1e-2), (0.5e-3, 5.0), (2e-4, 1e3), (1e-3, 1e-3)] {
                    let f = end_flange(
                        &tri,
                        &kind,
                        &ring,
                        &roller,
                        &Vec3::x(),
                        &p,
                        penetration,
                        (rx, ry),
                        &Vec3::y(),
                        &Vec3::zeros(),
                    );
                    let finite = f.normal.is_finite()
                        && f.tangential.iter().all(|x| x.is_finite())
                        && f.film.is_finite();
                    assert!(
                        finite,
                        "δ = {penetration}, R = ({rx}, {ry}), spin {spin}: {f:?}"
                    );
                    let hertz = EllipticalContact::new(
                        rx,
                        ry,
                        kind.e_prime,
                        EllipticalMethod::BreweHamrock,
                    )
                    .at_force(f.normal);
                    let bound = tri.boundary.mu_b0 * f.normal
                        + std::f64::consts::PI * hertz.semi_major * hertz.semi_minor * 3e7;
                    assert!(
                        f.tangential.norm() <= bound * (1.0 + 1e-9),
                        "{f:?} > {bound}"
                    );
                }
            }
        }
    }

    #[test]
    fn damped_force_is_elastic_at_rest_and_never_negative() {
        let f = damped_normal_force(100.0, 1e8, 1e-3, 0.1, 0.0);
        // ½(1 + sqrt(1 + ε²)) − 1 = ε²/4 = 1e-4.
        assert!((f / 100.0 - 1.0).abs() < 1.01e-4);
        for rate in [-10.0, -1.0, -0.1, 0.1, 1.0] {
            let f = damped_normal_force(100.0, 1e8, 1e-3, 0.1, rate);
            assert!(f > 0.0 && f.is_finite());
        }
        assert_eq!(damped_normal_force(0.0, 0.0, 1e-3, 0.1, -5.0), 0.0);
        // Approaching: c δ̇ with c = 2ζ sqrt(k m) = 2·0.1·sqrt(1e5) = 63.2 N s/m.
        let f = damped_normal_force(100.0, 1e8, 1e-3, 0.1, 0.1);
        assert!((f - (100.0 + 6.3246)).abs() < 0.02);
    }

    /// B1's inner race slice: ring A turning at 52 rad/s about x, roller B (R = 2.25 mm) on
    /// top of it at the gap −δ, at rest, the normal +y.
    fn inner_slice(penetration: f64, roller_spin: f64) -> (LineKind, Kinematics, Kinematics, Vec3) {
        let (r_race, r) = (10e-3, 2.2475e-3);
        let kind = LineKind {
            law: LinePowerLaw {
                k1: 1.3e-11,
                k2: 0.9,
            },
            e_prime: 2.3e11,
            r_eff: 1.0 / (1.0 / r + 1.0 / r_race),
            roughness: 0.16e-6,
            sharing: LoadSharing { b: 2.32, c: 0.97 },
            counter_rotating: false,
            rolling_resistance: true,
            mass_per_length: 0.62e-3 / 4.4e-3,
        };
        let ring = Kinematics {
            omega: Vec3::new(52.0, 0.0, 0.0),
            ..Kinematics::fixed()
        };
        let roller = Kinematics {
            center: Vec3::new(0.0, r_race + r - penetration, 0.0),
            omega: Vec3::new(roller_spin, 0.0, 0.0),
            ..Kinematics::fixed()
        };
        let location = Vec3::new(0.0, r_race - 0.5 * penetration, 0.0);
        (kind, ring, roller, location)
    }

    /// The forces of `law` (the slice's or the film's) on B1's inner race section.
    fn forces_at(
        penetration: f64,
        roller_spin: f64,
        law: fn(&Tribology, &LineKind, &Section) -> ContactForces,
    ) -> ContactForces {
        forces_with(&tribology(), penetration, roller_spin, law)
    }

    /// The slice of [`inner_slice`]'s bodies at P: normal +y, 0.22 mm long, rolling
    /// direction across the roller's axis.
    fn inner_section<'a>(
        ring: &'a Kinematics,
        roller: &'a Kinematics,
        p: Vec3,
        penetration: f64,
    ) -> Section<'a> {
        let n = Vec3::y();
        Section {
            a: ring,
            b: roller,
            normal: n,
            location: p,
            penetration,
            length: 0.22e-3,
            rolling: n.cross(&roller.axis).normalize(),
            frame: roller.frame_velocity(&p),
        }
    }

    /// [`forces_at`] with the tribology `tri`.
    fn forces_with(
        tri: &Tribology,
        penetration: f64,
        roller_spin: f64,
        law: fn(&Tribology, &LineKind, &Section) -> ContactForces,
    ) -> ContactForces {
        let (kind, ring, roller, p) = inner_slice(penetration, roller_spin);
        let section = inner_section(&ring, &roller, p, penetration);
        law(tri, &kind, &section)
    }

    /// Film and EHL forces of one slice, as the model sums them.
    fn slice_total(penetration: f64, roller_spin: f64) -> ContactForces {
        let mut f = forces_at(penetration, roller_spin, line_slice);
        f.add(&forces_at(penetration, roller_spin, film_slice));
        f
    }

    #[test]
    fn a_roller_lifted_one_micrometre_off_the_race_still_rolls_on_oil() {
        // Roller at rest 1 µm above the turning race: the film carries Martin's load for the
        // mean speed, and its shear drives the roller towards rolling (the force on the
        // roller points along the race surface's motion, +z at the top of a ring turning
        // about +x).
        let f = slice_total(-1e-6, 0.0);
        let (kind, ..) = inner_slice(-1e-6, 0.0);
        let u_m = 0.5 * 52.0 * 10e-3;
        let h = (1e-12f64 + 0.16e-6f64.powi(2)).sqrt();
        let martin = 4.894_97 * 0.0165 * u_m * kind.r_eff / h * 0.22e-3;
        assert!(
            (f.normal / martin - 1.0).abs() < 1e-3,
            "{} vs {martin}",
            f.normal
        );
        assert!(f.tangential.z > 1e-4, "{:?}", f.tangential);
        // It spins the roller about −x, as rolling on the race needs: (p − c) = −r·y, and
        // (−r y) × (+z) = −r x.
        let moment = (Vec3::new(0.0, -2.2475e-3, 0.0)).cross(&f.tangential);
        assert!(moment.x < 0.0);
    }

    #[test]
    fn film_and_contact_join_with_continuous_force_and_slope() {
        // The sum of the film and the EHL slice is continuous at δ = 0, and the film's own
        // slope vanishes there from both sides (its gap is floored and its fade starts flat),
        // so the slope of the sum is that of eq. 11, which falls to 0 as δ^0.11 at δ = 0.
        let spin = -52.0 * 10e-3 / 2.2475e-3;
        let e = 1e-13;
        let total = |delta: f64| slice_total(delta, spin).normal;
        let (below, above) = (total(-e), total(e));
        assert!((above - below).abs() < 1e-6 * below, "{below} {above}");
        let film = |delta: f64| forces_at(delta, spin, film_slice).normal;
        // Slope scale: Martin's load over σ (the film's own length scale).
        let scale = film(0.0) / 0.16e-6;
        let d = 1e-10;
        for slope in [(film(0.0) - film(-d)) / d, (film(d) - film(0.0)) / d] {
            assert!(slope.abs() < 2e-3 * scale, "{slope} vs {scale}");
        }
        // Over the whole fade the film's slope stays within its scale (no step).
        let steps: Vec<f64> = (0..=16)
            .map(|k| film(-0.16e-6 + k as f64 * 0.02e-6))
            .collect();
        let largest = steps
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        assert!(largest < 0.5 * film(0.0), "{steps:?}");
        // Deep in contact (δ ≥ σ) only the paper's laws act.
        let film = forces_at(0.5e-6, spin, film_slice);
        assert_eq!(film, ContactForces::default());
    }

    /// The moment about a body's own axis (through its centre `c`) of the force `f` at `p`
    /// and the couple `m`.
    fn axial_moment(body: &Kinematics, p: &Vec3, f: &Vec3, m: &Vec3) -> f64 {
        ((p - body.center).cross(f) + m).dot(&body.axis)
    }

    /// The forces of one slice of B1's inner race (`line_slice`, no hysteresis) with the
    /// roller rolling on the turning ring at δ = 2 µm, for each way of applying the
    /// rolling resistance: (the slice's forces, ring, roller, P, n).
    fn rolling_slice(
        how: RollingResistance,
    ) -> (ContactForces, Kinematics, Kinematics, Vec3, Vec3) {
        let mut tri = tribology();
        tri.hysteresis_coefficient = 0.0;
        tri.rolling_resistance = how;
        let (penetration, spin) = (2e-6, -52.0 * 10e-3 / 2.2475e-3);
        let (_, ring, roller, p) = inner_slice(penetration, spin);
        let forces = forces_with(&tri, penetration, spin, line_slice);
        (forces, ring, roller, p, Vec3::y())
    }

    /// The paper's rolling resistance (eq. 56: F_R·R on each body, as pure moments) does
    /// not conserve angular momentum: on the inner race the two moments about the bearing
    /// axis differ by F_R·(ρ_A − ρ_B), ρ the distances of P from the ring's and the
    /// roller's axes. The balanced one keeps each body's moment about its own axis (ring
    /// and roller alike, to round-off) and adds the force pair of the film's equilibrium,
    /// F_R·(ρ_A − ρ_B)/(ρ_A + ρ_B) on the roller along the surfaces' motion (closed form of
    /// [`rolling_resistance_balanced`] for pure rolling, F_A = F_B = F_R), so that the
    /// pair's net moment vanishes. F_R is read off the paper's moment on the ring.
    #[test]
    fn balanced_rolling_resistance_keeps_each_moment_and_conserves_angular_momentum() {
        let (paper, ring, roller, p, n) = rolling_slice(RollingResistance::Paper);
        let (balanced, ..) = rolling_slice(RollingResistance::Balanced);
        let (rho_a, rho_b) = (p.y, roller.center.y - p.y);
        let f_r = paper.moment_a.x.abs() / (p - ring.center).norm();
        assert!(f_r > 1e-4, "an EHL rolling force to check: {f_r} N");
        for (body, sign) in [(&ring, -1.0), (&roller, 1.0)] {
            let [m_paper, m_balanced] = [&paper, &balanced].map(|f| {
                let m = if sign > 0.0 { f.moment_b } else { f.moment_a };
                axial_moment(body, &p, &(sign * f.force_on_b(&n)), &m)
            });
            // The same moment by two sequences of a dozen operations: round-off of about
            // 1e-15 of it; bound 1e-12.
            assert!(
                (m_balanced - m_paper).abs() <= 1e-12 * m_paper.abs(),
                "{m_balanced} vs {m_paper}"
            );
        }
        let pair = balanced.tangential - paper.tangential;
        // Closed form against the code's ρ from the axes: round-off only; bound 1e-12 F_R.
        let expected = f_r * (rho_a - rho_b) / (rho_a + rho_b);
        let motion = ring.omega.cross(&(p - ring.center)).normalize();
        assert!(
            (pair.dot(&motion) - expected).abs() <= 1e-12 * f_r,
            "{pair:?} vs {expected}"
        );
        // Net moment of the pair about the bearing axis: the forces act at one point, so
        // only the couples count.
        let net = |f: &ContactForces| (f.moment_a + f.moment_b).x;
        let imbalance = f_r * (rho_a - rho_b);
        assert!(
            (net(&paper).abs() - imbalance).abs() <= 1e-9 * imbalance,
            "{} vs {imbalance}",
            net(&paper)
        );
        assert!(
            net(&balanced).abs() <= 1e-12 * imbalance,
            "{}",
            net(&balanced)
        );
    }

    /// The balanced law's rolling force is the pressure flow's shear, the same −(h/2)·∂p/∂x
    /// on both surfaces (Reynolds' velocity profile; Hamrock, Schmid & Jacobson 2004),
    /// against the entrainment u_m = (u_A + u_B)/2 whatever each surface's own speed. On
    /// B1's inner race section with a rolling force F: a roller that skids on the turning
    /// race (u_B = 0) feels the moment of −F·t at P about its axis, as a rolling one does
    /// (the paper's law, switched by the roller's own speed, gives it none); between
    /// surfaces moving against each other at equal speeds (u_m = 0) no rolling force acts.
    /// Round-off bound: 1e-12 of F·ρ.
    #[test]
    fn balanced_rolling_force_acts_against_the_entrainment_on_both_surfaces() {
        let mut tri = tribology();
        tri.rolling_resistance = RollingResistance::Balanced;
        let (_, ring, roller, p) = inner_slice(2e-6, 0.0);
        let n = Vec3::y();
        let section = inner_section(&ring, &roller, p, 2e-6);
        let t = section.rolling;
        let f = 1e-3;
        let u_race = 0.52;
        let with = |u_roller: f64| {
            let mut out = ContactForces::default();
            section.rolling_resistance(&mut out, &tri, (u_race, u_roller), 0.0, (0.0, f));
            out
        };
        let skid = with(0.0);
        let expected = (p - roller.center).cross(&(-f * t)).dot(&roller.axis);
        let on_roller = axial_moment(&roller, &p, &skid.force_on_b(&n), &skid.moment_b);
        assert!(expected.abs() > 1e-6, "{expected}");
        assert!(
            (on_roller - expected).abs() <= 1e-12 * expected.abs(),
            "{on_roller} vs {expected}"
        );
        // The ring feels the same shear at P about its own axis.
        let on_ring = axial_moment(&ring, &p, &(-skid.force_on_b(&n)), &skid.moment_a);
        let expected_ring = (p - ring.center).cross(&(-f * t)).dot(&ring.axis);
        assert!(
            (on_ring - expected_ring).abs() <= 1e-12 * expected_ring.abs(),
            "{on_ring} vs {expected_ring}"
        );
        // The paper's law gives the skidding roller nothing.
        let mut paper = tri.clone();
        paper.rolling_resistance = RollingResistance::Paper;
        let mut out = ContactForces::default();
        section.rolling_resistance(&mut out, &paper, (u_race, 0.0), 0.0, (0.0, f));
        assert_eq!(out.moment_b.dot(&roller.axis), 0.0);
        // No entrainment, no rolling force.
        let opposed = with(-u_race);
        assert_eq!(opposed.tangential, Vec3::zeros());
        assert_eq!(opposed.moment_a + opposed.moment_b, Vec3::zeros());
        assert_eq!(opposed.moment_b, Vec3::zeros());
    }

    proptest! {
        /// Any two bodies (a convex or a concave ring, or a second roller), any surface
        /// speeds and rolling forces: the balanced rolling resistance gives each body the
        /// moment F·ρ about its own axis of the shear F at P (F_A against A's motion, F_B
        /// against B's), with no net force or moment on the pair.
        #[test]
        fn balanced_rolling_resistance_is_the_shear_moment_in_equilibrium(
            rho_a in prop::sample::select(vec![-15e-3, -10e-3, 2.25e-3, 10e-3, 50e-3]),
            rho_b in 1e-3..5e-3f64,
            offset in -3e-3..3e-3f64,
            f_a in -0.5..0.5f64,
            f_b in -0.5..0.5f64,
            hysteresis in -1e-4..1e-4f64,
        ) {
            let n = Vec3::y();
            let p = Vec3::new(offset, 0.0, 0.0);
            // A's axis at P − ρ_A n, B's at P + ρ_B n, both along x; the centres off P
            // axially by different amounts.
            let a = Kinematics {
                center: Vec3::new(0.3e-3, -rho_a, 0.0),
                ..Kinematics::fixed()
            };
            let b = Kinematics {
                center: Vec3::new(-0.2e-3, rho_b, 0.0),
                ..Kinematics::fixed()
            };
            let section = Section {
                a: &a,
                b: &b,
                normal: n,
                location: p,
                penetration: 1e-6,
                length: 1e-4,
                rolling: n.cross(&b.axis),
                frame: Vec3::zeros(),
            };
            let f = rolling_resistance_balanced(&section, hysteresis, f_a, f_b);
            let t = section.rolling;
            // Moments of up to 0.5 N at 0.05 m plus the couple: 2.5e-2 N m through a few
            // operations, round-off of about 1e-17 N m; bound 1e-14 N m.
            let scale = 1e-14;
            // A's shear −F_A t at P about its axis point P − ρ_A n, and B's.
            let shear_a = (rho_a * n).cross(&(-f_a * t)).x;
            let shear_b = (-rho_b * n).cross(&(-f_b * t)).x;
            // The hysteresis couple against B's spin (sign of u_B, as `hysteresis`) and its
            // opposite on A; B's spin axis is +x here.
            let hysteresis_b = -hysteresis;
            let on_a = axial_moment(&a, &p, &(-f.tangential), &f.moment_a);
            let on_b = axial_moment(&b, &p, &f.tangential, &f.moment_b);
            prop_assert!((on_a - (shear_a - hysteresis_b)).abs() <= scale, "{on_a} vs {shear_a}");
            prop_assert!((on_b - (shear_b + hysteresis_b)).abs() <= scale, "{on_b} vs {shear_b}");
            prop_assert!((f.moment_a + f.moment_b).norm() <= scale);
        }
    }
}
