//! A frame's velocity held by its four-velocity's spatial part u = γβ, for frames so fast that
//! β itself cannot be written in `f64`: a point moving forward on a body that moves at
//! |β| = 1 − 10⁻¹⁶ (the rim of a rolling wheel, a thrusting rocket) moves at 1 − |β| ≈ 10⁻¹⁸,
//! and its β rounds to |β| = 1, where γ = 1/√(1 − β²) and the Lorentz matrix are infinite or
//! NaN. From u the Lorentz factor γ = √(1 + u²), the boost Λ (Eq. 2), the Doppler factors
//! (Eq. 3–4's time parts) and the aberration (Eq. 4) are written here without cancellation, with
//! γ − |u| = 1/(γ + |u|) and, for unit vectors, 1 − â·n = |â − n|²/2.

use glam::{DMat4, DQuat, DVec3, DVec4};

/// A velocity relative to S as the spatial part u = γβ of its four-velocity γ(1, β) (see the
/// module documentation); finite for every speed below light, however close.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FourVelocity {
    spatial: DVec3,
}

impl FourVelocity {
    /// At rest.
    pub const REST: Self = Self {
        spatial: DVec3::ZERO,
    };

    /// The velocity `beta` (|β| < 1), with γ = 1/√((1 − |β|)(1 + |β|)) (below Eq. 2).
    #[must_use]
    pub fn from_beta(beta: DVec3) -> Self {
        let speed = beta.length();
        Self {
            spatial: beta / ((1.0 - speed) * (1.0 + speed)).sqrt(),
        }
    }

    /// The velocity whose four-velocity has the spatial part `spatial` (γβ, any finite vector).
    #[must_use]
    pub const fn from_spatial(spatial: DVec3) -> Self {
        Self { spatial }
    }

    /// The velocity of rapidity `rapidity` along the unit vector `direction`: u = sinh η · â.
    #[must_use]
    pub fn from_rapidity(direction: DVec3, rapidity: f64) -> Self {
        Self {
            spatial: rapidity.sinh() * direction,
        }
    }

    /// The spatial part u = γβ.
    #[must_use]
    pub const fn spatial(&self) -> DVec3 {
        self.spatial
    }

    /// The Lorentz factor γ = √(1 + u²).
    #[must_use]
    pub fn gamma(&self) -> f64 {
        (1.0 + self.spatial.length_squared()).sqrt()
    }

    /// β = u/γ (its length may round to 1 beyond γ ≈ 10⁸; compute with the methods here).
    #[must_use]
    pub fn beta(&self) -> DVec3 {
        self.spatial / self.gamma()
    }

    /// The opposite velocity, −β.
    #[must_use]
    pub fn reversed(&self) -> Self {
        Self {
            spatial: -self.spatial,
        }
    }

    /// Λ_β of Eq. 2 in terms of u: γβ = u and γ²/(γ+1)·ββᵀ = uuᵀ/(γ+1), so
    /// Λ = ((γ, uᵀ), (u, 1₃ + uuᵀ/(γ+1))): it takes four-vectors of the frame moving with this
    /// velocity to S.
    #[must_use]
    pub fn boost(&self) -> DMat4 {
        let (gamma, u) = (self.gamma(), self.spatial);
        let k = 1.0 / (gamma + 1.0);
        let column = |axis: DVec3, component: f64| {
            let spatial = axis + k * component * u;
            DVec4::new(component, spatial.x, spatial.y, spatial.z)
        };
        DMat4::from_cols(
            DVec4::new(gamma, u.x, u.y, u.z),
            column(DVec3::X, u.x),
            column(DVec3::Y, u.y),
            column(DVec3::Z, u.z),
        )
    }

    /// The velocity relative to S of a body moving with `within` (|β| < 1) relative to the frame
    /// that moves with this velocity: the spatial part of Λ γ_v(1, v) (Eq. 3 applied to the
    /// body's four-velocity), which stays exact where the composed β would round to 1.
    #[must_use]
    pub fn compose(&self, within: Self) -> Self {
        let inner = within.spatial;
        let four = self.boost() * DVec4::new(within.gamma(), inner.x, inner.y, inner.z);
        Self {
            spatial: DVec3::new(four.y, four.z, four.w),
        }
    }

    /// The Wigner rotation R of composing this velocity with `within`: the pure boosts satisfy
    /// Λ(self)·Λ(within) = Λ(self ⊕ within)·R, so spatial coordinates of the body's rest frame
    /// reached from the moving frame by a pure boost are turned by R into those of its rest
    /// frame reached from S by a pure boost. About the axis β_within × β by the angle ε with
    /// (γ the composed Lorentz factor, γ_f and γ_w the two others; Thomas–Wigner rotation)
    /// sin ε = γ_f γ_w (1 + γ + γ_f + γ_w) |β × β_within| / ((1 + γ)(1 + γ_f)(1 + γ_w)),
    /// cos ε = (1 + γ + γ_f + γ_w)² / ((1 + γ)(1 + γ_f)(1 + γ_w)) − 1, finite for every speed.
    #[must_use]
    pub fn wigner_rotation(&self, within: Self) -> DQuat {
        let (gf, gw) = (self.gamma(), within.gamma());
        let g = self.compose(within).gamma();
        let axis = within.spatial.cross(self.spatial);
        let length = axis.length();
        if length == 0.0 {
            return DQuat::IDENTITY;
        }
        let sum = 1.0 + g + gf + gw;
        let denominator = (1.0 + g) * (1.0 + gf) * (1.0 + gw);
        // |β × β_w| γ_f γ_w = |u × u_w|.
        let sin = sum * length / denominator;
        let cos = sum * sum / denominator - 1.0;
        DQuat::from_axis_angle(axis / length, sin.atan2(cos))
    }

    /// γ(1 − β·n) for the unit vector `direction` n, as γ − u·n = 1/(γ + |u|) + |u|·|û − n|²/2:
    /// positive and accurate for every n (no cancellation where n is along β).
    #[must_use]
    pub fn gamma_one_minus_dot(&self, direction: DVec3) -> f64 {
        let speed = self.spatial.length();
        if speed == 0.0 {
            return 1.0;
        }
        let along = self.spatial / speed;
        1.0 / (self.gamma() + speed) + speed * 0.5 * (along - direction).length_squared()
    }

    /// The Doppler factor D = 1/(γ(1 − β·n)) of light that reaches an observer at rest in S
    /// travelling along the unit vector `propagation` (in S) from a source moving with this
    /// velocity (Eq. 4's time part; [`crate::doppler_factor`] in terms of β).
    #[must_use]
    pub fn doppler_factor(&self, propagation: DVec3) -> f64 {
        1.0 / self.gamma_one_minus_dot(propagation)
    }

    /// The Doppler factor D = γ(1 − β·n) with which a receiver moving with this velocity sees
    /// light propagating along the unit vector `propagation` (in S) from a source at rest in S
    /// (Eq. 3's time part, the first factor of Eq. 17; [`crate::receiver_doppler`]).
    #[must_use]
    pub fn receiver_doppler(&self, propagation: DVec3) -> f64 {
        self.gamma_one_minus_dot(propagation)
    }

    /// Aberration (Eq. 4): the unit propagation direction in S of light propagating along the
    /// unit vector `direction_rest` in the frame moving with this velocity
    /// ([`crate::aberrate`] in terms of β). With a = û·n′ and p = n′ − a·û, Eq. 4's space part
    /// over its time part is (û(|u| + γa) + p) / (γ + |u|a), and near a = −1 both
    /// |u| + γa = γ(1 + a) − 1/(γ + |u|) and γ + |u|a = 1/(γ + |u|) + |u|(1 + a), with
    /// 1 + a = |û + n′|²/2, are taken without cancellation.
    #[must_use]
    pub fn aberrate(&self, direction_rest: DVec3) -> DVec3 {
        let speed = self.spatial.length();
        if speed == 0.0 {
            return direction_rest;
        }
        let along = self.spatial / speed;
        let gamma = self.gamma();
        let a = along.dot(direction_rest);
        let across = direction_rest - a * along;
        let one_plus_a = 0.5 * (along + direction_rest).length_squared();
        let slow = 1.0 / (gamma + speed);
        let parallel = if a < 0.0 {
            gamma * one_plus_a - slow
        } else {
            speed + gamma * a
        };
        let time = if a < 0.0 {
            slow + speed * one_plus_a
        } else {
            gamma + speed * a
        };
        ((parallel / time) * along + across / time).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::{aberrate, doppler_factor, receiver_doppler};
    use crate::lorentz::{compose_velocities, lorentz_factor, lorentz_matrix};
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn unit(v: [f64; 3]) -> Option<DVec3> {
        let v = DVec3::from(v);
        (v.length() > 0.1).then(|| v.normalize())
    }

    proptest! {
        /// At everyday speeds every method agrees with its β form (light.rs, lorentz.rs).
        #[test]
        fn agrees_with_the_beta_formulas(
            beta in prop::array::uniform3(-0.57f64..0.57),
            within in prop::array::uniform3(-0.57f64..0.57),
            n in prop::array::uniform3(-1.0f64..1.0),
        ) {
            let Some(n) = unit(n) else { return Ok(()) };
            let (beta, within) = (DVec3::from(beta), DVec3::from(within));
            let u = FourVelocity::from_beta(beta);
            prop_assert!((u.beta() - beta).length() < 1e-14);
            assert_relative_eq!(u.gamma(), lorentz_factor(beta), max_relative = 1e-12);
            let (ours, theirs) = (u.boost().to_cols_array(), lorentz_matrix(beta).to_cols_array());
            for (a, b) in ours.iter().zip(theirs) {
                prop_assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} vs {b}");
            }
            assert_relative_eq!(u.doppler_factor(n), doppler_factor(beta, n), max_relative = 1e-13);
            assert_relative_eq!(u.receiver_doppler(n), receiver_doppler(beta, n), max_relative = 1e-13);
            prop_assert!((u.aberrate(n) - aberrate(beta, n)).length() < 1e-12);
            let composed = u.compose(FourVelocity::from_beta(within)).beta();
            prop_assert!((composed - compose_velocities(beta, within)).length() < 1e-12);
        }
    }

    proptest! {
        /// Λ(f)·Λ(w) = Λ(f ⊕ w)·R: at everyday speeds Λ(−(f ⊕ w))·Λ(f)·Λ(w), taken as matrices,
        /// is the Wigner rotation (no time part), whose sense and angle this checks.
        #[test]
        fn the_wigner_rotation_is_what_composed_boosts_leave(
            frame in prop::array::uniform3(-0.57f64..0.57),
            within in prop::array::uniform3(-0.57f64..0.57),
        ) {
            let f = FourVelocity::from_beta(DVec3::from(frame));
            let w = FourVelocity::from_beta(DVec3::from(within));
            let left = f.compose(w).reversed().boost() * f.boost() * w.boost();
            let rotation = glam::DMat3::from_quat(f.wigner_rotation(w));
            for (i, column) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
                let expected = rotation * column;
                let got = left.col(i + 1);
                prop_assert!(got.x.abs() < 1e-12, "{left}");
                prop_assert!((DVec3::new(got.y, got.z, got.w) - expected).length() < 1e-12,
                    "{left} vs {rotation}");
            }
        }
    }

    /// A speed |β| in [0.999999, 1 − 1.1·10⁻¹⁶] (the largest `f64` below 1), as 1 − |β|
    /// drawn on a log scale so that every decade is met.
    fn near_light_speed() -> impl Strategy<Value = f64> {
        (-16.0f64..-6.0).prop_map(|e| (1.0 - 10f64.powf(e)).min(0.999_999_999_999_999_9))
    }

    /// The rapidity η = artanh β = ½ ln((1 + β)/(1 − β)), 1 − β exact near 1.
    fn rapidity(speed: f64) -> f64 {
        0.5 * ((1.0 + speed) / (1.0 - speed)).ln()
    }

    proptest! {
        /// At |β| from 1 − 10⁻⁶ to 1 − 1.1·10⁻¹⁶ along any direction â, and a body moving forward
        /// along â on that frame as fast: collinear rapidities add (Eq. 3 on the four-velocity), and
        /// the Doppler factor along any unit n is that of rapidity η, 1/(γ(1 − β·n)) (Eq. 4's
        /// time part) with γ(1 − β·n) = e^(−η)(1 + â·n)/2 + e^(η)(1 − â·n)/2, a sum of
        /// positive terms, however fast the composed body goes (its β may round to 1).
        #[test]
        fn near_light_speed_compositions_and_doppler_factors_are_finite_and_exact(
            frame_speed in near_light_speed(),
            body_speed in near_light_speed(),
            direction in prop::array::uniform3(-1.0f64..1.0),
            n in prop::array::uniform3(-1.0f64..1.0),
        ) {
            let (Some(along), Some(n)) = (unit(direction), unit(n)) else { return Ok(()) };
            // The speeds as written in f64 (|β| of the vector, not the number drawn).
            let (frame_beta, body_beta) = (frame_speed * along, body_speed * along);
            prop_assume!(frame_beta.length() < 1.0 && body_beta.length() < 1.0);
            let frame = FourVelocity::from_beta(frame_beta);
            let body = frame.compose(FourVelocity::from_beta(body_beta));
            let eta = rapidity(frame_beta.length()) + rapidity(body_beta.length());
            prop_assert!((body.spatial() - eta.sinh() * along).length()
                <= 1e-9 * eta.cosh() + 1e-9, "{body:?} vs η = {eta}");
            assert_relative_eq!(body.gamma(), eta.cosh(), max_relative = 1e-9);
            let (plus, minus) = ((along + n).length_squared() / 2.0, (along - n).length_squared() / 2.0);
            let expected = 1.0 / ((-eta).exp() * plus / 2.0 + eta.exp() * minus / 2.0);
            let doppler = body.doppler_factor(n);
            prop_assert!(doppler.is_finite() && doppler > 0.0, "{doppler}");
            assert_relative_eq!(doppler, expected, max_relative = 1e-6);
            assert_relative_eq!(body.receiver_doppler(n) * body.reversed().receiver_doppler(-n),
                1.0 / (doppler * body.reversed().doppler_factor(-n)), max_relative = 1e-6);
        }
    }

    /// A body moving forward at 0.9 on a frame at |β| = 1 − 1.1·10⁻¹⁶: its β rounds to |β| = 1
    /// (the β formulas give ∞ and NaN), its four-velocity stays exact: collinear rapidities add,
    /// and the Doppler factors are e^(±η) head-on and 1/γ across, with aberration sending light
    /// emitted backwards in the body's frame forwards in S.
    #[test]
    fn stays_finite_and_exact_where_beta_rounds_to_one() {
        let frame = FourVelocity::from_beta(DVec3::new(0.999_999_999_999_999_9, 0.0, 0.0));
        let body = frame.compose(FourVelocity::from_beta(DVec3::new(0.9, 0.0, 0.0)));
        let eta = 0.999_999_999_999_999_9f64.atanh() + 0.9f64.atanh();
        let rounded = lorentz_factor(body.beta());
        // ∞, NaN or far off (the nearest β below 1 has γ = 6.7·10⁷, not 3·10⁸).
        let near = (rounded / eta.cosh() - 1.0).abs() < 0.5;
        assert!(!near, "β's own γ: {rounded}");
        assert_relative_eq!(body.spatial().x, eta.sinh(), max_relative = 1e-9);
        assert_relative_eq!(body.gamma(), eta.cosh(), max_relative = 1e-9);
        assert_relative_eq!(
            body.doppler_factor(DVec3::X),
            eta.exp(),
            max_relative = 1e-9
        );
        assert_relative_eq!(
            body.doppler_factor(-DVec3::X),
            (-eta).exp(),
            max_relative = 1e-9
        );
        assert_relative_eq!(
            body.receiver_doppler(DVec3::X),
            (-eta).exp(),
            max_relative = 1e-9
        );
        assert_relative_eq!(
            body.doppler_factor(DVec3::Y),
            1.0 / eta.cosh(),
            max_relative = 1e-9
        );
        // Light emitted at 90° + θ′ in the body's frame: in S, cos θ = (cos θ′ + β)/(1 + β cos θ′),
        // i.e. tan(θ/2) = e^(−η) tan(θ′/2).
        let angle = 3.0f64;
        let seen = body.aberrate(DVec3::new(angle.cos(), angle.sin(), 0.0));
        let half = ((-eta).exp() * (angle / 2.0).tan()).atan();
        assert_relative_eq!(seen.y.atan2(seen.x), 2.0 * half, max_relative = 1e-9);
        // Back to the body's frame with the reversed velocity.
        let back = body.reversed().aberrate(seen);
        assert_relative_eq!(back.y.atan2(back.x), angle, max_relative = 1e-6);
        assert!(body.boost().to_cols_array().iter().all(|v| v.is_finite()));
        // Sideways on that frame the Wigner rotation is finite and tends to the angle the
        // ultra-relativistic limit gives (cos ε → 1/γ_w for γ_f → ∞ with β_w ⟂ β_f).
        let across = FourVelocity::from_beta(DVec3::new(0.0, 0.0, 0.6));
        let (axis, angle) = frame.wigner_rotation(across).to_axis_angle();
        assert_relative_eq!(angle.cos(), 0.8, max_relative = 1e-6);
        assert_relative_eq!(axis.y.abs(), 1.0, max_relative = 1e-12);
    }
}
