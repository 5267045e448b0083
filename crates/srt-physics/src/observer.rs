//! A moving observer: Poincaré transformations composed as matrices, their split into a boost
//! and a spatial (Wigner) rotation, and the rest frame of an object as seen from an observer that
//! moves through the scene's world frame W.
//!
//! The renderers work in the observer's rest frame S (the paper's setting: the observer at rest,
//! every object in its own frame S′, Eq. 1). A scene with an observer moving with β_o relative to
//! W is brought into that setting exactly: every object's transformation S′ → W (Eq. 1) is
//! followed by W → S, and the product, a general proper orthochronous Poincaré transformation, is
//! split into a pure boost times a rotation of S′ (the Thomas–Wigner rotation). Velocities are
//! never added; the boosts are multiplied as 4 × 4 matrices.

use glam::{DMat3, DMat4, DVec3, DVec4};

use crate::event::Event;
use crate::frame::{Frame, FrameError};
use crate::lorentz::{lorentz_matrix, validate_beta};

/// A Poincaré transformation x ↦ Λ x + a of events (Eq. 1 with a general Lorentz matrix Λ and a
/// translation a that may have a time part).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Poincare {
    /// The Lorentz matrix Λ, acting on columns (ct, x, y, z).
    pub lorentz: DMat4,
    /// The translation a = (ct, x, y, z), added after Λ.
    pub translation: DVec4,
}

impl Poincare {
    /// The identity: every event keeps its coordinates.
    pub const IDENTITY: Self = Self {
        lorentz: DMat4::IDENTITY,
        translation: DVec4::ZERO,
    };

    /// The transformation S′ → S of `frame`: x = Λ_β x′ + (0, **a**) (Eq. 1).
    #[must_use]
    pub fn of_frame(frame: &Frame) -> Self {
        let offset = frame.offset();
        Self {
            lorentz: frame.rest_to_observer_matrix(),
            translation: DVec4::new(0.0, offset.x, offset.y, offset.z),
        }
    }

    /// The image of `event`: Λ x + a.
    #[must_use]
    pub fn apply(&self, event: Event) -> Event {
        Event::from_four_vector(self.lorentz * event.to_four_vector() + self.translation)
    }

    /// `self` followed by `next`: x ↦ Λ₂(Λ₁ x + a₁) + a₂ = (Λ₂Λ₁) x + (Λ₂ a₁ + a₂), the group law
    /// of the Poincaré group.
    #[must_use]
    pub fn then(&self, next: &Self) -> Self {
        Self {
            lorentz: next.lorentz * self.lorentz,
            translation: next.lorentz * self.translation + next.translation,
        }
    }
}

/// Splits a proper orthochronous Lorentz matrix Λ into a pure boost and a spatial rotation,
/// Λ = Λ_w · diag(1, R) (the polar decomposition; Jackson, *Classical Electrodynamics*, 3rd ed.,
/// §11.7; Sexl & Urbantke, *Relativity, Groups, Particles*, §2.6). Returns (w, R).
///
/// The boost's velocity is read off the first column, Λ (1, 0) = γ_w (1, w): the frame's origin
/// moves with w. Writing Λ_w with Eq. 2 and multiplying out gives the blocks
/// Λ₀₀ = γ_w, Λₛ₀ = γ_w w, Λ₀ₛ = γ_w wᵀR, Λₛₛ = (1₃ + γ_w²/(γ_w+1) w wᵀ) R, so
/// R = Λₛₛ − Λₛ₀ Λ₀ₛ / (1 + Λ₀₀) without a second matrix product.
///
/// For a product of two boosts Λ_u Λ_v, w is the relativistic composition u ⊕ v and R the
/// Thomas–Wigner rotation (Rhodes and Semon, *Am. J. Phys.* 72, 943 (2004)).
#[must_use]
pub fn boost_and_rotation(lorentz: DMat4) -> (DVec3, DMat3) {
    // glam is column-major: col(c)[r] is the entry in row r, column c.
    let gamma = lorentz.col(0).x;
    let boost_column = spatial(lorentz.col(0));
    let time_row = DVec3::new(lorentz.col(1).x, lorentz.col(2).x, lorentz.col(3).x);
    let space_block = DMat3::from_cols(
        spatial(lorentz.col(1)),
        spatial(lorentz.col(2)),
        spatial(lorentz.col(3)),
    );
    // Λₛ₀ Λ₀ₛ is the outer product of the boost column with the time row.
    let outer = DMat3::from_cols(
        boost_column * time_row.x,
        boost_column * time_row.y,
        boost_column * time_row.z,
    );
    (
        boost_column / gamma,
        space_block - outer * (1.0 / (1.0 + gamma)),
    )
}

/// The spatial part (x, y, z) of a four-vector column stored as (ct, x, y, z).
const fn spatial(v: DVec4) -> DVec3 {
    DVec3::new(v.y, v.z, v.w)
}

/// The rest frame S of an observer moving with velocity β_o through the world frame W, observing
/// at the event E (given in W).
///
/// S has axes parallel to W's as seen by the observer (S is reached from W by the pure boost
/// Λ_−β_o), and its origin is chosen so that E has the same coordinates in S as in W:
/// x_S = Λ_−β_o (x_W − E) + E. The observer rests in S at E's position, and S's time is the
/// observer's own clock, reading ct_E at E.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingObserver {
    beta: DVec3,
    event: Event,
    world_to_observer: Poincare,
}

/// An object's rest frame as the moving observer describes it: the pure boost `frame` after a
/// rotation of the object's rest-frame coordinates.
///
/// A point at x′ in the object's rest frame (as given in W) rests at x″ = `rotation` · x′ in
/// `frame`'s rest coordinates, and the rest event (ct′, x′) is the event
/// `frame.to_observer((ct′ + rest_time_shift, rotation · x′))` in S. The time shift only renames
/// the rest frame's clock; a static object is the same at every rest time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelativeFrame {
    /// The object's motion relative to the observer: velocity and offset in S (Eq. 1).
    pub frame: Frame,
    /// The rotation R of the object's rest-frame coordinates (the Thomas–Wigner rotation).
    pub rotation: DMat3,
    /// The shift of the object's rest-frame clock, ct″ = ct′ + shift.
    pub rest_time_shift: f64,
}

impl MovingObserver {
    /// The rest frame of an observer moving with `beta` (relative to W) and observing at `event`
    /// (in W).
    ///
    /// # Errors
    /// [`FrameError::NonFinite`] for NaN or infinite input, [`FrameError::Superluminal`] for
    /// |β_o| ≥ 1.
    pub fn new(beta: DVec3, event: Event) -> Result<Self, FrameError> {
        let beta = validate_beta(beta)?;
        if !event.is_finite() {
            return Err(FrameError::NonFinite {
                what: "observation event",
            });
        }
        let to_event = event.to_four_vector();
        let boost = lorentz_matrix(-beta);
        let world_to_observer = Poincare {
            lorentz: boost,
            translation: to_event - boost * to_event,
        };
        Ok(Self {
            beta,
            event,
            world_to_observer,
        })
    }

    /// The observer's velocity β_o relative to W.
    #[must_use]
    pub const fn beta(&self) -> DVec3 {
        self.beta
    }

    /// The observation event, in W (and, by the choice of origin, in S).
    #[must_use]
    pub const fn event(&self) -> Event {
        self.event
    }

    /// The transformation W → S: x_S = Λ_−β_o (x_W − E) + E.
    #[must_use]
    pub const fn world_to_observer(&self) -> Poincare {
        self.world_to_observer
    }

    /// The event `world` (in W) in the observer's rest frame S.
    #[must_use]
    pub fn to_observer(&self, world: Event) -> Event {
        self.world_to_observer.apply(world)
    }

    /// The transformation S → W, the inverse of [`MovingObserver::world_to_observer`]:
    /// x_W = Λ_β_o (x_S − E) + E (Eq. 1 with the observer's frame as S′). The identity, to the
    /// last bit, for an observer at rest (β_o = 0 exactly).
    #[must_use]
    pub fn observer_to_world(&self) -> Poincare {
        if self.beta == DVec3::ZERO {
            return Poincare::IDENTITY;
        }
        let to_event = self.event.to_four_vector();
        let boost = lorentz_matrix(self.beta);
        Poincare {
            lorentz: boost,
            translation: to_event - boost * to_event,
        }
    }

    /// The rest frame of an object whose frame relative to W is `world_frame`, as this observer
    /// describes it.
    ///
    /// The object's transformation S′ → S is the product P = (W → S) ∘ (S′ → W), with Lorentz
    /// part Λ = Λ_−β_o Λ_β and translation A = Λ_−β_o ((0, **a**) − E) + E. Splitting
    /// Λ = Λ_w diag(1, R) ([`boost_and_rotation`]) and A = Λ_w (τ, 0) + (0, **a**″) with
    /// τ = A₀/γ_w, **a**″ = **A** − w A₀ gives x_S = Λ_w (ct′ + τ, R x′) + (0, **a**″): the pure boost
    /// of `Frame::new(w, a″)` applied to the rotated rest coordinates.
    ///
    /// An observer at rest (β_o = 0 exactly) returns `world_frame` itself, the identity rotation
    /// and no time shift, so scenes without observer motion are unchanged to the last bit; an
    /// object at rest in W (β = 0 exactly) moves with exactly −β_o and is not rotated.
    ///
    /// # Errors
    /// [`FrameError::Superluminal`] if the relative speed rounds to 1 (both speeds within about
    /// 1e-16 of c), [`FrameError::NonFinite`] if an offset is so large that the product
    /// overflows.
    pub fn relative_frame(&self, world_frame: &Frame) -> Result<RelativeFrame, FrameError> {
        if self.beta == DVec3::ZERO {
            return Ok(RelativeFrame {
                frame: *world_frame,
                rotation: DMat3::IDENTITY,
                rest_time_shift: 0.0,
            });
        }
        let total = Poincare::of_frame(world_frame).then(&self.world_to_observer);
        let (velocity, rotation) = if world_frame.beta() == DVec3::ZERO {
            // Λ_−β_o Λ_0 is the pure boost Λ_−β_o: no rotation, exactly.
            (-self.beta, DMat3::IDENTITY)
        } else {
            boost_and_rotation(total.lorentz)
        };
        let shift = total.translation;
        let offset = spatial(shift) - velocity * shift.x;
        let frame = Frame::new(velocity, offset)?;
        Ok(RelativeFrame {
            frame,
            rotation,
            rest_time_shift: shift.x / frame.gamma(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn an_observer_at_rest_changes_nothing() {
        let observer = MovingObserver::new(DVec3::ZERO, Event::new(3.0, DVec3::ONE)).unwrap();
        let frame = Frame::new(DVec3::new(0.3, -0.2, 0.1), DVec3::new(1.0, 2.0, 3.0)).unwrap();
        let relative = observer.relative_frame(&frame).unwrap();
        assert_eq!(relative.frame, frame);
        assert_eq!(relative.rotation, DMat3::IDENTITY);
        assert_eq!(relative.rest_time_shift, 0.0);
    }

    #[test]
    fn the_way_back_to_the_world_undoes_the_way_in() {
        let event = Event::new(4.0, DVec3::new(1.0, -2.0, 0.5));
        let observer = MovingObserver::new(DVec3::new(0.3, 0.6, -0.2), event).unwrap();
        for world in [
            Event::new(-7.0, DVec3::new(3.0, 1.0, 2.0)),
            Event::new(12.5, DVec3::new(-40.0, 0.0, 9.0)),
        ] {
            let back = observer
                .observer_to_world()
                .apply(observer.to_observer(world));
            assert_relative_eq!(back.ct, world.ct, epsilon = 1e-12);
            assert!((back.position - world.position).length() < 1e-12);
        }
        let resting = MovingObserver::new(DVec3::ZERO, event).unwrap();
        assert_eq!(resting.observer_to_world(), Poincare::IDENTITY);
    }

    #[test]
    fn the_observation_event_keeps_its_coordinates() {
        let event = Event::new(4.0, DVec3::new(1.0, -2.0, 0.5));
        let observer = MovingObserver::new(DVec3::new(0.0, 0.9, 0.0), event).unwrap();
        let mapped = observer.to_observer(event);
        assert_relative_eq!(mapped.ct, event.ct, epsilon = 1e-12);
        assert!((mapped.position - event.position).length() < 1e-12);
    }

    #[test]
    fn an_object_at_rest_in_the_world_moves_opposite_to_the_observer() {
        let beta = DVec3::new(0.6, 0.0, 0.0);
        let observer = MovingObserver::new(beta, Event::new(0.0, DVec3::ZERO)).unwrap();
        let world = Frame::new(DVec3::ZERO, DVec3::new(0.0, 5.0, 0.0)).unwrap();
        let relative = observer.relative_frame(&world).unwrap();
        assert!((relative.frame.beta() + beta).length() < 1e-15);
        assert!((relative.rotation - DMat3::IDENTITY).abs_diff_eq(DMat3::ZERO, 1e-15));
        // (0, 0, 5, 0) is unmoved by a boost along x, so the object's origin passes it at ct = 0.
        assert!((relative.frame.offset() - DVec3::new(0.0, 5.0, 0.0)).length() < 1e-14);
    }

    #[test]
    fn rejects_bad_observer_velocities() {
        let event = Event::new(0.0, DVec3::ZERO);
        assert!(matches!(
            MovingObserver::new(DVec3::new(0.0, 1.0, 0.0), event),
            Err(FrameError::Superluminal { .. })
        ));
        assert!(matches!(
            MovingObserver::new(DVec3::new(f64::NAN, 0.0, 0.0), event),
            Err(FrameError::NonFinite { .. })
        ));
        assert!(matches!(
            MovingObserver::new(DVec3::ZERO, Event::new(f64::INFINITY, DVec3::ZERO)),
            Err(FrameError::NonFinite { .. })
        ));
    }
}
