//! A request checked against the device's limits before anything is allocated, so that what
//! the adapter cannot serve comes back as a typed [`GpuError::ExceedsLimit`] that names the limit
//! and the amounts, instead of a wgpu validation error after the fact.

use crate::context::GpuContext;
use crate::error::GpuError;

/// The limits of one device and the adapter's name, for the checks and their messages.
#[derive(Debug, Clone)]
pub struct DeviceLimits {
    /// The limits the device was opened with.
    pub limits: wgpu::Limits,
    /// The adapter's name.
    pub adapter: String,
}

/// Bytes of one row of `width` texels of `texel_bytes` each in a texture-to-buffer copy, padded
/// to wgpu's `COPY_BYTES_PER_ROW_ALIGNMENT`.
#[must_use]
pub fn padded_row_bytes(width: u32, texel_bytes: u32) -> u64 {
    (u64::from(width) * u64::from(texel_bytes))
        .next_multiple_of(u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT))
}

impl DeviceLimits {
    /// The limits of `ctx`'s device.
    #[must_use]
    pub fn of(ctx: &GpuContext) -> Self {
        Self {
            limits: ctx.device.limits(),
            adapter: ctx.adapter_info.name.clone(),
        }
    }

    /// `Ok` when `requested` ≤ `limit`, else the error naming `what()` and the limit.
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when `requested` > `limit`.
    pub fn at_most(
        &self,
        what: impl FnOnce() -> String,
        requested: u64,
        unit: &'static str,
        limit: u64,
        limit_name: &'static str,
    ) -> Result<(), GpuError> {
        if requested <= limit {
            Ok(())
        } else {
            Err(GpuError::ExceedsLimit {
                what: what(),
                requested,
                unit,
                limit,
                limit_name,
                adapter: self.adapter.clone(),
            })
        }
    }

    /// A 2D texture of `width` × `height` texels (`what` names it, e.g. "render target").
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when a side exceeds `max_texture_dimension_2d`.
    pub fn check_texture(&self, what: &str, width: u32, height: u32) -> Result<(), GpuError> {
        let limit = u64::from(self.limits.max_texture_dimension_2d);
        for (side, value) in [("width", width), ("height", height)] {
            self.at_most(
                || format!("the {side} of the {width} × {height} {what}"),
                u64::from(value),
                "pixels",
                limit,
                "max_texture_dimension_2d",
            )?;
        }
        Ok(())
    }

    /// A buffer of `bytes` (`what` names it).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when it exceeds `max_buffer_size`.
    pub fn check_buffer(&self, what: impl Fn() -> String, bytes: u64) -> Result<(), GpuError> {
        self.at_most(
            what,
            bytes,
            "bytes",
            self.limits.max_buffer_size,
            "max_buffer_size",
        )
    }

    /// A storage buffer of `bytes` bound whole (`what` names it).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when it exceeds `max_storage_buffer_binding_size` or
    /// `max_buffer_size`.
    pub fn check_storage_buffer(
        &self,
        what: impl Fn() -> String,
        bytes: u64,
    ) -> Result<(), GpuError> {
        self.at_most(
            &what,
            bytes,
            "bytes",
            self.limits.max_storage_buffer_binding_size,
            "max_storage_buffer_binding_size",
        )?;
        self.check_buffer(what, bytes)
    }

    /// Colour and depth targets of `width` × `height` and the buffer their colour is read back
    /// through (`texel_bytes` per colour texel).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] for the first limit exceeded.
    pub fn check_render_target(
        &self,
        width: u32,
        height: u32,
        texel_bytes: u32,
    ) -> Result<(), GpuError> {
        self.check_texture("render target", width, height)?;
        self.check_buffer(
            || format!("the readback buffer of the {width} × {height} render target"),
            padded_row_bytes(width, texel_bytes) * u64::from(height),
        )
    }

    /// The workgroup grid (x, y) that runs `invocations` invocations in workgroups of
    /// `workgroup_size`, x as large as allowed (`what` names the pass).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] when even a square grid would exceed
    /// `max_compute_workgroups_per_dimension`.
    pub fn workgroup_grid(
        &self,
        what: impl Fn() -> String,
        invocations: u64,
        workgroup_size: u32,
    ) -> Result<(u32, u32), GpuError> {
        let max = self.limits.max_compute_workgroups_per_dimension.max(1);
        let groups = invocations.div_ceil(u64::from(workgroup_size.max(1)));
        let x = groups.clamp(1, u64::from(max));
        let y = groups.div_ceil(x);
        self.at_most(
            || format!("{} ({invocations} invocations)", what()),
            y,
            "rows of workgroups",
            u64::from(max),
            "max_compute_workgroups_per_dimension",
        )?;
        // Both fit in u32: x ≤ max and y ≤ max.
        Ok((x as u32, y as u32))
    }

    /// A count of `unit` that a draw call takes as `u32` (`what` names it).
    ///
    /// # Errors
    /// [`GpuError::ExceedsLimit`] above `u32::MAX`.
    pub fn check_u32(
        &self,
        what: impl Fn() -> String,
        count: u64,
        unit: &'static str,
    ) -> Result<u32, GpuError> {
        self.at_most(
            what,
            count,
            unit,
            u64::from(u32::MAX),
            "the u32 counts of draw calls",
        )?;
        Ok(count as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> DeviceLimits {
        DeviceLimits {
            limits: wgpu::Limits {
                max_texture_dimension_2d: 8192,
                max_buffer_size: 1 << 20,
                max_storage_buffer_binding_size: 1 << 16,
                max_compute_workgroups_per_dimension: 100,
                ..wgpu::Limits::downlevel_defaults()
            },
            adapter: "test adapter".into(),
        }
    }

    #[test]
    fn a_render_target_wider_than_the_texture_limit_names_the_limit() {
        let error = small().check_render_target(16384, 2, 16).unwrap_err();
        let GpuError::ExceedsLimit {
            requested,
            limit,
            limit_name,
            ..
        } = &error
        else {
            panic!("{error:?}");
        };
        assert_eq!((*requested, *limit), (16384, 8192));
        assert_eq!(*limit_name, "max_texture_dimension_2d");
        assert_eq!(
            error.to_string(),
            "the width of the 16384 × 2 render target is 16384 pixels, but this adapter \
             (test adapter) allows at most 8192 (max_texture_dimension_2d)"
        );
        assert!(
            small()
                .check_render_target(8192, 8192, 16)
                .is_err_and(|e| e.to_string().contains("max_buffer_size"))
        );
        small().check_render_target(64, 64, 16).unwrap();
    }

    #[test]
    fn storage_buffers_are_held_to_the_binding_limit() {
        let what = || "the vertex buffer".to_owned();
        small().check_storage_buffer(what, 1 << 16).unwrap();
        let error = small()
            .check_storage_buffer(what, (1 << 16) + 1)
            .unwrap_err();
        assert!(
            matches!(
                error,
                GpuError::ExceedsLimit {
                    limit_name: "max_storage_buffer_binding_size",
                    ..
                }
            ),
            "{error}"
        );
    }

    #[test]
    fn workgroup_grids_grow_in_y_up_to_the_limit() {
        let limits = small();
        let what = || "the pass".to_owned();
        assert_eq!(limits.workgroup_grid(what, 1, 64).unwrap(), (1, 1));
        assert_eq!(limits.workgroup_grid(what, 64 * 100, 64).unwrap(), (100, 1));
        assert_eq!(
            limits.workgroup_grid(what, 64 * 100 + 1, 64).unwrap(),
            (100, 2)
        );
        assert_eq!(
            limits.workgroup_grid(what, 64 * 100 * 100, 64).unwrap(),
            (100, 100)
        );
        assert!(limits.workgroup_grid(what, 64 * 100 * 100 + 1, 64).is_err());
    }

    #[test]
    fn padded_rows_are_multiples_of_the_copy_alignment() {
        assert_eq!(padded_row_bytes(1, 16), 256);
        assert_eq!(padded_row_bytes(16, 16), 256);
        assert_eq!(padded_row_bytes(17, 16), 512);
        assert_eq!(padded_row_bytes(64, 4), 256);
    }
}
