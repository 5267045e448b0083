//! Reading glTF accessors into `f64` values, bounds-checked throughout.
//!
//! The `gltf` crate's own reader relies on debug assertions and `unwrap`s for type and stride
//! mismatches that malformed files contain (and that its validation does not catch), so we read
//! the bytes ourselves: any component type (with the spec's normalisation rules), any byte stride
//! no smaller than an element, and sparse accessors.

use gltf::Accessor;
use gltf::accessor::DataType;
use gltf::accessor::sparse::IndexType;

/// Accessors without a buffer view are all zeros (unless sparse); more elements than this in such
/// an accessor are rejected rather than allocated.
const MAX_VIEWLESS_COUNT: usize = 1 << 24;

/// Reads accessor `accessor` as `N`-component elements. `normalize` applies the glTF rules for
/// normalised integer components (`false` for indices, which are read as they are).
///
/// # Errors
/// A message if the accessor does not have `N` components, its data lies outside its buffer
/// view or buffer, its stride is smaller than an element, or a sparse index is out of range.
pub(super) fn read<const N: usize>(
    accessor: &Accessor<'_>,
    buffers: &[Vec<u8>],
    normalize: bool,
) -> Result<Vec<[f64; N]>, String> {
    let index = accessor.index();
    let components = accessor.dimensions().multiplicity();
    if components != N {
        return Err(format!(
            "accessor {index} has {components} components per element where {N} are expected"
        ));
    }
    let data_type = accessor.data_type();
    let normalized = normalize && accessor.normalized();
    let component_size = data_type.size();
    let element_size = component_size * N;
    let count = accessor.count();
    let mut values = match accessor.view() {
        Some(view) => {
            let bytes = view_bytes(&view, buffers).ok_or_else(|| {
                format!(
                    "accessor {index}: buffer view {} lies outside its buffer",
                    view.index()
                )
            })?;
            let stride = view.stride().unwrap_or(element_size);
            if stride < element_size {
                return Err(format!(
                    "accessor {index}: byte stride {stride} is smaller than an element ({element_size} bytes)"
                ));
            }
            read_elements::<N>(
                bytes,
                accessor.offset(),
                stride,
                count,
                data_type,
                normalized,
            )
            .ok_or_else(|| {
                format!(
                    "accessor {index}: {count} elements do not fit in buffer view {}",
                    view.index()
                )
            })?
        }
        None => {
            if count > MAX_VIEWLESS_COUNT {
                return Err(format!("accessor {index} has no data but {count} elements"));
            }
            vec![[0.0; N]; count]
        }
    };
    if let Some(sparse) = accessor.sparse() {
        let sparse_count = sparse.count();
        let indices = sparse.indices();
        let index_type = match indices.index_type() {
            IndexType::U8 => DataType::U8,
            IndexType::U16 => DataType::U16,
            IndexType::U32 => DataType::U32,
        };
        let bad = || format!("accessor {index}: sparse data lies outside its buffer");
        let index_bytes = view_bytes(&indices.view(), buffers).ok_or_else(bad)?;
        let targets = read_elements::<1>(
            index_bytes,
            indices.offset(),
            index_type.size(),
            sparse_count,
            index_type,
            false,
        )
        .ok_or_else(bad)?;
        let sparse_values = sparse.values();
        let value_bytes = view_bytes(&sparse_values.view(), buffers).ok_or_else(bad)?;
        let replacements = read_elements::<N>(
            value_bytes,
            sparse_values.offset(),
            element_size,
            sparse_count,
            data_type,
            normalized,
        )
        .ok_or_else(bad)?;
        for ([target], value) in targets.into_iter().zip(replacements) {
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "indices are read from unsigned integers of at most 32 bits"
            )]
            let slot = values.get_mut(target as usize).ok_or_else(|| {
                format!("accessor {index}: sparse index {target} is not below its count {count}")
            })?;
            *slot = value;
        }
    }
    Ok(values)
}

/// Reads a scalar index accessor (unsigned integer components only).
///
/// # Errors
/// As [`read`], and if the components are not unsigned integers.
pub(super) fn read_indices(
    accessor: &Accessor<'_>,
    buffers: &[Vec<u8>],
) -> Result<Vec<u32>, String> {
    if !matches!(
        accessor.data_type(),
        DataType::U8 | DataType::U16 | DataType::U32
    ) {
        return Err(format!(
            "index accessor {} has {:?} components; indices must be unsigned integers",
            accessor.index(),
            accessor.data_type()
        ));
    }
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "values read from unsigned integers of at most 32 bits"
    )]
    let indices = read::<1>(accessor, buffers, false)?
        .into_iter()
        .map(|[i]| i as u32)
        .collect();
    Ok(indices)
}

/// The bytes of a buffer view, or `None` if it does not fit in its buffer.
pub(super) fn view_bytes<'b>(
    view: &gltf::buffer::View<'_>,
    buffers: &'b [Vec<u8>],
) -> Option<&'b [u8]> {
    let buffer = buffers.get(view.buffer().index())?;
    let end = view.offset().checked_add(view.length())?;
    buffer.get(view.offset()..end)
}

/// Reads `count` elements of `N` components of type `data_type`, the first at `offset`, one every
/// `stride` bytes. `None` if they do not all lie within `bytes`.
fn read_elements<const N: usize>(
    bytes: &[u8],
    offset: usize,
    stride: usize,
    count: usize,
    data_type: DataType,
    normalized: bool,
) -> Option<Vec<[f64; N]>> {
    let component_size = data_type.size();
    if count > 0 {
        let last = offset.checked_add(stride.checked_mul(count - 1)?)?;
        let end = last.checked_add(component_size * N)?;
        if end > bytes.len() {
            return None;
        }
    }
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let start = offset + i * stride;
        let mut element = [0.0; N];
        for (c, value) in element.iter_mut().enumerate() {
            let at = start + c * component_size;
            *value = component(bytes.get(at..at + component_size)?, data_type, normalized);
        }
        out.push(element);
    }
    Some(out)
}

/// One little-endian component, normalised per the glTF specification if asked to.
fn component(bytes: &[u8], data_type: DataType, normalized: bool) -> f64 {
    let b = |i: usize| bytes.get(i).copied().unwrap_or(0);
    match data_type {
        DataType::I8 => {
            let v = f64::from(i8::from_le_bytes([b(0)]));
            if normalized { (v / 127.0).max(-1.0) } else { v }
        }
        DataType::U8 => {
            let v = f64::from(b(0));
            if normalized { v / 255.0 } else { v }
        }
        DataType::I16 => {
            let v = f64::from(i16::from_le_bytes([b(0), b(1)]));
            if normalized {
                (v / 32767.0).max(-1.0)
            } else {
                v
            }
        }
        DataType::U16 => {
            let v = f64::from(u16::from_le_bytes([b(0), b(1)]));
            if normalized { v / 65535.0 } else { v }
        }
        DataType::U32 => f64::from(u32::from_le_bytes([b(0), b(1), b(2), b(3)])),
        DataType::F32 => f64::from(f32::from_le_bytes([b(0), b(1), b(2), b(3)])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strided_elements_are_read_and_bounds_checked() {
        let mut bytes = Vec::new();
        for v in [1.0f32, 2.0, 3.0, 99.0, 4.0, 5.0, 6.0, 99.0] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let values = read_elements::<3>(&bytes, 0, 16, 2, DataType::F32, false).unwrap();
        assert_eq!(values, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
        assert!(read_elements::<3>(&bytes, 4, 16, 2, DataType::F32, false).is_some());
        assert!(read_elements::<3>(&bytes, 8, 16, 2, DataType::F32, false).is_none());
        assert!(read_elements::<3>(&bytes, usize::MAX, 16, 2, DataType::F32, false).is_none());
        assert!(read_elements::<3>(&bytes, 0, usize::MAX, 3, DataType::F32, false).is_none());
        assert_eq!(
            read_elements::<3>(&bytes, 0, 16, 0, DataType::F32, false),
            Some(vec![])
        );
    }

    /// A document with one 64-byte buffer, views over it and the given accessors.
    fn document(views: &str, accessors: &str) -> gltf::Document {
        let json = format!(
            r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": 64}}],
                "bufferViews": {views}, "accessors": {accessors}}}"#
        );
        gltf::Gltf::from_slice(json.as_bytes()).unwrap().document
    }

    fn buffer() -> Vec<Vec<u8>> {
        let mut bytes = Vec::new();
        for v in 0..12u8 {
            bytes.extend_from_slice(&f32::from(v).to_le_bytes());
        }
        bytes.extend_from_slice(&[2, 0, 0, 0]); // sparse index (u8) at 48
        bytes.extend_from_slice(&[0; 12]); // sparse value at 52: zeros
        vec![bytes]
    }

    #[test]
    fn sparse_accessors_replace_elements() {
        let doc = document(
            r#"[{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 4},
                {"buffer": 0, "byteOffset": 52, "byteLength": 12}]"#,
            r#"[{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5121},
                            "values": {"bufferView": 2}}},
                {"componentType": 5126, "count": 3, "type": "VEC3",
                 "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5121},
                            "values": {"bufferView": 0}}}]"#,
        );
        let accessors: Vec<_> = doc.accessors().collect();
        let values = read::<3>(&accessors[0], &buffer(), true).unwrap();
        assert_eq!(
            values,
            [
                [0.0, 1.0, 2.0],
                [3.0, 4.0, 5.0],
                [0.0; 3],
                [9.0, 10.0, 11.0]
            ]
        );
        // Without a buffer view the base is zeros.
        let values = read::<3>(&accessors[1], &buffer(), true).unwrap();
        assert_eq!(values, [[0.0; 3], [0.0; 3], [0.0, 1.0, 2.0]]);
    }

    #[test]
    fn malformed_accessors_are_errors() {
        let doc = document(
            r#"[{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 32, "byteLength": 64},
                {"buffer": 0, "byteLength": 48, "byteStride": 4}]"#,
            r#"[{"bufferView": 0, "componentType": 5126, "count": 5, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5126, "count": 1, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"},
                {"bufferView": 0, "componentType": 5126, "count": 2, "type": "VEC2"},
                {"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR"}]"#,
        );
        let accessors: Vec<_> = doc.accessors().collect();
        let buffers = buffer();
        let too_many = read::<3>(&accessors[0], &buffers, true).unwrap_err();
        assert!(too_many.contains("do not fit"), "{too_many}");
        let outside = read::<3>(&accessors[1], &buffers, true).unwrap_err();
        assert!(outside.contains("outside"), "{outside}");
        let stride = read::<3>(&accessors[2], &buffers, true).unwrap_err();
        assert!(stride.contains("stride"), "{stride}");
        let dims = read::<3>(&accessors[3], &buffers, true).unwrap_err();
        assert!(dims.contains("components"), "{dims}");
        let float_indices = read_indices(&accessors[4], &buffers).unwrap_err();
        assert!(float_indices.contains("unsigned"), "{float_indices}");
    }

    #[test]
    fn normalised_integers_follow_the_spec() {
        assert_eq!(component(&[255], DataType::U8, true), 1.0);
        assert_eq!(component(&[0x80], DataType::I8, true), -1.0);
        assert_eq!(component(&[0xff, 0xff], DataType::U16, true), 1.0);
        assert_eq!(component(&[0x01, 0x80], DataType::I16, true), -1.0);
        assert_eq!(component(&[7, 0], DataType::U16, false), 7.0);
    }
}
