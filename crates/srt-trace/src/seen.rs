//! What a pixel sees of *time*: the event at which the light it receives left a surface. The
//! tracer finds that event exactly for every hit (Eq. 5–8: the backward light cone of the
//! observation event meets the surface's worldline); [`SeenEvent`] (made by
//! [`crate::Tracer::seen_event`]) writes it out in the
//! scene's own terms — world time, the object's proper time, apparent distance, the Doppler
//! factor of the light and which object — for `srt render --aov` and `srt.render(aov=True)`
//! (docs/scene-format.md, "Per-pixel channels").

/// The emission event a pixel's centre sees, in the scene's terms (c = 1: times are ct, in
/// scene units of length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeenEvent {
    /// The seen object's index in scene order.
    pub object: usize,
    /// The world-frame time ct_W of the emission event (W: the frame the scene file gives
    /// times and positions in; the observer's frame S when the observer rests in W).
    pub emission_ct: f64,
    /// The object's proper time at the emission event: the event's time ct′ in the object's
    /// rest frame S′ (whose clocks are synchronised in S′ and read 0 at t = t′ = 0 at its
    /// origin), which a clock resting on the object at that point shows.
    pub proper_time: f64,
    /// The apparent distance, ct_obs − ct_emission in the observer's frame S (the light's travel
    /// time; Eq. 8).
    pub distance: f64,
    /// The Doppler factor D of the light from the surface to the observer (Eq. 4; D > 1 is a
    /// blue shift): the shift `doppler` and `searchlight` show, without the lamp's.
    pub doppler: f64,
}
