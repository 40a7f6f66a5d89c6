//! Tp from GPU timestamps written at the start and end of the render pass.

/// Bytes of the two resolved timestamps.
pub(crate) const TIMESTAMP_BYTES: u64 = 2 * wgpu::QUERY_SIZE as u64;

/// A pair of timestamp queries around the render pass, resolved into a buffer that the
/// frame's readback copies from.
pub(crate) struct GpuTimer {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    /// Nanoseconds per timestamp tick.
    period_ns: f64,
}

impl GpuTimer {
    /// A timer, if the device has [`wgpu::Features::TIMESTAMP_QUERY`].
    pub(crate) fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let query_set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("render pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamp resolve"),
            size: TIMESTAMP_BYTES,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(Self {
            query_set,
            resolve,
            period_ns: f64::from(queue.get_timestamp_period()),
        })
    }

    /// The timestamp writes for the pass to be timed.
    pub(crate) fn pass_writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    /// The timestamp write at the start of the first of several passes to be timed.
    pub(crate) fn begin_writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: None,
        }
    }

    /// The timestamp write at the end of the last of several passes to be timed.
    pub(crate) fn end_writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: None,
            end_of_pass_write_index: Some(1),
        }
    }

    /// Resolves the two timestamps and copies them to `destination` at `offset`.
    pub(crate) fn resolve(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        destination: &wgpu::Buffer,
        offset: u64,
    ) {
        encoder.resolve_query_set(&self.query_set, 0..2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, destination, offset, TIMESTAMP_BYTES);
    }

    /// Milliseconds between the two resolved timestamps in `bytes`.
    pub(crate) fn elapsed_ms(&self, bytes: &[u8]) -> Option<f64> {
        ticks_to_ms(bytes, self.period_ns)
    }
}

/// Milliseconds between the two little-endian u64 timestamps at the start of `bytes` at
/// `period_ns` per tick, or None when they make no sense (missing, zero or backwards).
fn ticks_to_ms(bytes: &[u8], period_ns: f64) -> Option<f64> {
    let [begin, end]: [u64; 2] =
        bytemuck::pod_read_unaligned(bytes.get(..TIMESTAMP_BYTES as usize)?);
    (begin != 0 && end > begin).then(|| (end - begin) as f64 * period_ns * 1e-6)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stamps(begin: u64, end: u64) -> Vec<u8> {
        bytemuck::cast_slice(&[begin, end]).to_vec()
    }

    #[test]
    fn converts_ticks_with_the_period() {
        assert_eq!(ticks_to_ms(&stamps(1_000, 3_001_000), 1.0), Some(3.0));
        assert_eq!(ticks_to_ms(&stamps(10, 110), 40.0), Some(0.004));
    }

    #[test]
    fn rejects_unwritten_or_backwards_stamps() {
        assert_eq!(ticks_to_ms(&stamps(0, 5), 1.0), None);
        assert_eq!(ticks_to_ms(&stamps(9, 5), 1.0), None);
        assert_eq!(ticks_to_ms(&stamps(9, 9), 1.0), None);
        assert_eq!(ticks_to_ms(&[0; 8], 1.0), None);
    }
}
