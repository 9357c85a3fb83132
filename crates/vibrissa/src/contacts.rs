//! Each contact of a drag's contact set at a row or at a slip (issue 31): where it touches, its
//! forces in the surface's local frame, how it holds, and the friction coefficient of that state.

use crate::chain::{ContactSet, Mode};
use crate::watch::ContactForce;
use serde::Serialize;
use std::fmt;

/// How a contact holds on the surface. `dir` is the way it moves along the surface (`+1`:
/// towards `+x`, `−1`: towards `−x`); its friction force `T` has that sign (`T > 0` holds the rod
/// back towards `−x`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "state", rename_all = "snake_case")]
pub enum Hold {
    /// Holds without slip (a tip stuck at its place, a side rolling without slip): its friction
    /// is whatever the equilibrium needs, `|T| ≤ μs N`.
    Stuck,
    /// Slides with kinetic friction: `T = dir·μk N` (a side that formed needing more than μs,
    /// or, where a slip ends, the contact that slid until kinetic friction holds it).
    Sliding {
        /// The way it slides (±1).
        dir: f64,
    },
    /// Drives a slip in progress: its place moved the way `dir` along the surface with the foot
    /// held (the quasi-static slide); it needs `dir·T ≥ μk N` until the slip ends where
    /// `dir·T = μk N`.
    Slipping {
        /// The way it slips (±1).
        dir: f64,
    },
    /// Frictionless: `T = 0`.
    Free,
}

impl Hold {
    /// `stuck`, `sliding`, `slipping` or `free`.
    pub fn name(self) -> &'static str {
        match self {
            Hold::Stuck => "stuck",
            Hold::Sliding { .. } => "sliding",
            Hold::Slipping { .. } => "slipping",
            Hold::Free => "free",
        }
    }
}

/// One contact of a drag at a row or a slip. Forces in the surface's local frame at the contact
/// point (docs/model.md, "Contact and friction"): the normal `n = (−sin θ, cos θ)`, the tangent
/// `t = −(cos θ, sin θ)`, `θ = atan h'(x)`, the force on the rod `F = −N n + T t`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ContactState {
    /// Arc length on the rod (1: the tip).
    pub s: f64,
    /// Whether it is the tip.
    pub tip: bool,
    /// Lab x of the contact point (a round tip: the point of its disk that touches the surface,
    /// `P + r·n(x_c)` from the rod's end `P`).
    pub x: f64,
    /// Height of the contact point (as `x`: on the rod, or on a round tip's disk).
    pub y: f64,
    /// Normal force, `N ≥ 0` while the contact is compressive (the surface pushes; 0: lift-off).
    pub normal: f64,
    /// Tangential (friction) force along `t` (`> 0`: the surface holds the rod back towards
    /// `−x`).
    pub tangential: f64,
    /// How it holds.
    pub hold: Hold,
    /// The friction coefficient of its state at its place: μs for a stuck contact (its slip
    /// threshold), μk for a sliding or slipping one, 0 for a frictionless one.
    pub mu: f64,
    /// The inner end of a stretch lying on the surface (contact label `stretch`): the arc length
    /// of its outer end, where the unloaded rest begins (`s`..`lies_to` on the surface; its `N`,
    /// `T` the stretch's resultant). `None` for a point contact (and left out of JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lies_to: Option<f64>,
    /// The inner end of a lying stretch: the friction ratio `gμ` it needs to hold (stuck) or
    /// slides with (sliding), signed as `T`. Its friction law is this ratio's, not `|T| ≤ μ N`:
    /// the surface's curvature takes up a part of its resultant without friction (docs/model.md,
    /// "A stretch that slides"). `None` for a point contact (and left out of JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_ratio: Option<f64>,
}

impl fmt::Display for ContactState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} at s = {} ({}, {}): N = {:e}, T = {:e}, {}",
            if self.tip { "tip" } else { "side" },
            self.s,
            self.x,
            self.y,
            self.normal,
            self.tangential,
            self.hold.name()
        )?;
        match self.hold {
            Hold::Sliding { dir } | Hold::Slipping { dir } => {
                write!(f, " towards {}x", if dir < 0.0 { "-" } else { "+" })?
            }
            Hold::Stuck | Hold::Free => {}
        }
        write!(f, ", mu = {}", self.mu)?;
        if let Some(s2) = self.lies_to {
            write!(f, ", lying on the surface to s = {s2}")?;
        }
        match self.friction_ratio {
            Some(r) => write!(f, ", friction ratio {r}"),
            None => Ok(()),
        }
    }
}

/// The contacts of `set` at a point whose watch found the forces `forces`, their holds from
/// their modes.
pub(crate) fn states(set: &ContactSet, forces: &[ContactForce]) -> Vec<ContactState> {
    set.contacts
        .iter()
        .zip(forces)
        .enumerate()
        .map(|(j, (ct, c))| {
            let (hold, mu) = match ct.mode {
                Mode::Stuck(_) | Mode::Rolling(_) => (Hold::Stuck, c.mu_s),
                Mode::Sliding(r) => (Hold::Sliding { dir: r.signum() }, r.abs()),
                Mode::Free => (Hold::Free, 0.0),
            };
            ContactState {
                s: c.s,
                tip: ct.tip,
                x: c.x,
                y: c.y,
                normal: c.normal,
                tangential: c.tangential,
                hold,
                mu,
                lies_to: (set.lain() == Some(j)).then_some(c.lies_to),
                friction_ratio: (set.lain() == Some(j)).then_some(c.stretch_mu),
            }
        })
        .collect()
}

/// `states` with the stuck contacts' slip threshold `mu_s` where it is the phase's: the tip's,
/// and off a friction texture (`textured` false) every side's (a textured side keeps the
/// texture's μs at its place).
pub(crate) fn with_threshold(
    mut states: Vec<ContactState>,
    mu_s: f64,
    textured: bool,
) -> Vec<ContactState> {
    for c in states.iter_mut().filter(|c| c.hold == Hold::Stuck) {
        if c.tip || !textured {
            c.mu = mu_s;
        }
    }
    states
}

/// `states` with contact `j` (if there is one) holding as `hold` with the coefficient `mu`.
pub(crate) fn with_hold(
    mut states: Vec<ContactState>,
    j: usize,
    hold: Hold,
    mu: f64,
) -> Vec<ContactState> {
    if let Some(c) = states.get_mut(j) {
        c.hold = hold;
        c.mu = mu;
    }
    states
}
