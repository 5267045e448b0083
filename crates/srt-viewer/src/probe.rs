//! The probe: what the picture shows at one pixel, computed exactly on the CPU by the reference
//! tracer ([`srt_trace::Tracer::hit_at_pixel`], the viewing ray `srt render --backend cpu` casts
//! through the pixel's centre) — which object, when its light left it, how far it travelled,
//! and how the Doppler and searchlight effects change it there. No UI: [`probe`] returns a
//! [`Probe`], and [`Probe::lines`] words it for the panel.

use glam::DVec3;
use srt_physics::reflection_doppler;
use srt_scene::Scene;
use srt_trace::Tracer;

/// The visible band, in nanometres (the range of the CIE 1931 observer the colours use).
pub const VISIBLE_NM: (f64, f64) = (380.0, 780.0);

/// What is seen through one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct Probe {
    /// The object's name.
    pub object: String,
    /// The velocity of the surface point relative to the observer at the emission event, in
    /// units of c: the object's, or for a spinning or thrusting body the point's own
    /// ([`srt_trace::Tracer::surface_at`]).
    pub beta: DVec3,
    /// Where the point is seen (the emission event's position in S, Eq. 8).
    pub apparent_position: DVec3,
    /// World time ct (in the scene's frame W, the observer's when it rests there) at which the
    /// light seen left the surface (Eq. 7–8; [`srt_trace::SeenEvent`], as `srt render --aov`).
    pub emission_ct: f64,
    /// The proper time there: what a clock riding on the surface point showed as the light left
    /// it.
    pub proper_time: f64,
    /// How far the light travelled to the observer (= ct_obs − ct_emission, Eq. 6).
    pub apparent_distance: f64,
    /// Doppler factor D = ω_received/ω_emitted of light leaving the surface towards the
    /// observer (Eq. 4, [`srt_physics::doppler_factor`]).
    pub doppler: f64,
    /// Combined Doppler factor of light from the scene's light source reflected here to the
    /// observer (Eq. 17, [`reflection_doppler`]); it sets the colour the renderers show.
    pub reflected_doppler: f64,
}

impl Probe {
    /// The searchlight factor of radiance leaving the surface towards the observer: D⁴ of
    /// [`Probe::doppler`] (radiance integrated over wavelength; per unit wavelength it is D⁵,
    /// Eq. 9 of the paper after Weiskopf et al. 1999).
    #[must_use]
    pub fn searchlight(&self) -> f64 {
        self.doppler.powi(4)
    }

    /// The band, in nanometres, that light seen as visible (380–780 nm) had where the Doppler
    /// factor `doppler` began: λ_emitted = D · λ_received (D = λ′/λ, §3.3 of the paper).
    #[must_use]
    pub fn band_at(doppler: f64) -> (f64, f64) {
        (VISIBLE_NM.0 * doppler, VISIBLE_NM.1 * doppler)
    }

    /// The probe in words for the panel, one line each.
    #[must_use]
    pub fn lines(&self) -> Vec<String> {
        vec![
            format!(
                "{} (this point moving at {:.4}c relative to you)",
                self.object,
                self.beta.length()
            ),
            format!(
                "light left it at ct = {:.3} and travelled {:.3} (the apparent distance)",
                self.emission_ct, self.apparent_distance
            ),
            format!(
                "its own clock read ct' = {:.3} then (its proper time)",
                self.proper_time
            ),
            format!(
                "Doppler factor from the surface to you D = {:.4}; searchlight D^4 = {:.4} \
                 (radiance)",
                self.doppler,
                self.searchlight()
            ),
            format!(
                "light source to surface to you (Eq. 17): D = {:.4}",
                self.reflected_doppler
            ),
            format!(
                "visible light here left the light source at {}",
                format_band(Self::band_at(self.reflected_doppler))
            ),
            format!(
                "and left the surface at {}",
                format_band(Self::band_at(self.doppler))
            ),
        ]
    }
}

/// What the pixel (`x`, `y`) of a `width` × `height` picture of `scene` shows: `None` for the
/// background (or a pixel outside the picture).
#[must_use]
pub fn probe(scene: &Scene, width: u32, height: u32, x: u32, y: u32) -> Option<Probe> {
    let tracer = Tracer::new(scene);
    let hit = tracer.hit_at_pixel(width, height, x, y)?;
    let object = scene.objects.get(hit.object)?;
    let beta = tracer.surface_at(&hit).velocity.beta();
    let apparent_position = hit.emission.position;
    let seen = tracer.seen_event(&hit);
    // Propagation directions in S, as the shading uses them (§4.2): light → surface and
    // surface → observer.
    let incident = (apparent_position - scene.light.position).normalize_or_zero();
    let outgoing = (scene.observer.position - apparent_position).normalize_or_zero();
    Some(Probe {
        object: object.name.clone(),
        beta,
        apparent_position,
        emission_ct: seen.emission_ct,
        proper_time: seen.proper_time,
        apparent_distance: seen.distance,
        doppler: seen.doppler,
        reflected_doppler: reflection_doppler(beta, incident, outgoing),
    })
}

/// A wavelength band given in nanometres, in the unit that suits it: `380–780 nm`,
/// `1.66–3.40 µm`, `12.3–25.2 mm`.
#[must_use]
pub fn format_band((low, high): (f64, f64)) -> String {
    let (scale, unit) = if low >= 1e6 {
        (1e-6, "mm")
    } else if low >= 1e3 {
        (1e-3, "µm")
    } else if low >= 1.0 {
        (1.0, "nm")
    } else {
        (1e3, "pm")
    };
    let (low, high) = (low * scale, high * scale);
    let decimals = if low >= 100.0 {
        0
    } else if low >= 10.0 {
        1
    } else {
        2
    };
    format!("{low:.decimals$}–{high:.decimals$} {unit}")
}

#[cfg(test)]
mod tests {
    use srt_physics::doppler_factor;
    use srt_scene::builtin::find_builtin;

    use super::*;

    fn fig7() -> Scene {
        find_builtin("fig7").unwrap().build().unwrap().0
    }

    #[test]
    fn bands_are_written_in_a_unit_that_suits_them() {
        assert_eq!(format_band(Probe::band_at(1.0)), "380–780 nm");
        assert_eq!(format_band(Probe::band_at(4.37)), "1.66–3.41 µm");
        assert_eq!(format_band(Probe::band_at(0.5)), "190–390 nm");
        assert_eq!(format_band(Probe::band_at(0.001)), "380–780 pm");
        assert_eq!(format_band(Probe::band_at(50_000.0)), "19.0–39.0 mm");
    }

    #[test]
    fn a_pixel_on_the_cube_gives_the_cube_and_its_doppler_factors() {
        let scene = fig7();
        let (width, height) = (64, 48);
        let found = probe(&scene, width, height, width / 2, height / 2).expect("the cube");
        assert_eq!(found.object, "cube");
        let observer = scene.observer.position;
        let outgoing = (observer - found.apparent_position).normalize();
        let beta = DVec3::new(0.0, 0.95, 0.0);
        assert!((found.beta - beta).length() < 1e-12);
        assert!((found.doppler - doppler_factor(beta, outgoing)).abs() < 1e-12);
        // Approaching at 0.95c almost head-on: D close to √(1.95/0.05) = 6.24.
        assert!(
            found.doppler > 5.0 && found.doppler < 6.25,
            "{}",
            found.doppler
        );
        assert!((found.searchlight() - found.doppler.powi(4)).abs() < 1e-9);
        // Light travel: the distance travelled is the distance to where it is seen, and the
        // light left that long before the observation.
        let distance = (found.apparent_position - observer).length();
        assert!((found.apparent_distance - distance).abs() < 1e-9);
        assert!((found.emission_ct - (scene.observer.time - distance)).abs() < 1e-9);
        // Eq. 17 with the light at (90, 0, 9.8).
        let incident = (found.apparent_position - scene.light.position).normalize();
        let expected = reflection_doppler(beta, incident, outgoing);
        assert!((found.reflected_doppler - expected).abs() < 1e-12);
        let lines = found.lines().join("\n");
        let band = format_band(Probe::band_at(found.reflected_doppler));
        assert!(
            lines.contains(&format!(
                "visible light here left the light source at {band}"
            )),
            "{lines}"
        );
    }

    #[test]
    fn the_background_gives_nothing() {
        let scene = fig7();
        assert_eq!(probe(&scene, 64, 48, 0, 0), None);
        assert_eq!(probe(&scene, 64, 48, 64, 0), None);
    }
}

#[cfg(test)]
mod moving_body_tests {
    use super::*;

    #[test]
    fn the_probe_gives_a_spinning_points_own_velocity() {
        let text = r#"
            [observer]
            position = [0.0, -6.0, 0.0]
            look_at = [0.0, 0.0, 0.0]
            [[object]]
            shape = { type = "cube", size = 1.6 }
            spin = { axis = [0.0, 0.0, 1.0], rate = 0.5 }
        "#;
        let description = srt_scene::SceneDescription::from_toml_str(text, "test").unwrap();
        let (scene, _) = description.build(std::path::Path::new(".")).unwrap();
        // The object rests; a point left of the axis on the face towards the observer moves at
        // ω·(its distance from the axis) across the line of sight.
        let found = probe(&scene, 64, 48, 24, 24).unwrap();
        assert!(found.beta.length() > 0.05, "{}", found.beta);
        let tracer = Tracer::new(&scene);
        let hit = tracer.hit_at_pixel(64, 48, 24, 24).unwrap();
        let state = tracer.surface_at(&hit);
        let speed = 0.5 * DVec3::new(state.body.x, state.body.y, 0.0).length();
        assert!(
            (found.beta.length() - speed).abs() < 1e-9,
            "{} vs {speed}",
            found.beta
        );
    }
}
