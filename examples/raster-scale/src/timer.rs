//! A frame's GPU time: timestamps around the frame's passes where the adapter has them,
//! else the wall time from submission to completion. A timestamp reading longer than the
//! wall time around it (impossible) or not increasing is replaced by the wall time.

/// Bytes of the two resolved timestamps.
const STAMP_BYTES: u64 = 16;

/// Where a frame's time came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeSource {
    /// GPU timestamps around the passes.
    Timestamps,
    /// Host wall time from submission until the GPU finished.
    WallClock,
}

/// The timestamp queries of a frame and the buffers they are read through.
pub struct Timestamps {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f64,
}

impl Timestamps {
    /// Timestamps on `device`, or None when it lacks [`wgpu::Features::TIMESTAMP_QUERY`].
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: STAMP_BYTES,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(Self {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: buffer(
                "timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "timestamp readback",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            period_ns: f64::from(queue.get_timestamp_period()),
        })
    }

    /// The write at the start of the frame's first pass.
    pub fn begin(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: None,
        }
    }

    /// The write at the end of the frame's last pass.
    pub fn end(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: None,
            end_of_pass_write_index: Some(1),
        }
    }

    /// Records the copy of the two timestamps to the readback buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.query_set, 0..2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, STAMP_BYTES);
    }

    /// The milliseconds between the timestamps of the finished frame, or None when they make
    /// no sense. The GPU must be done with the frame (the caller waited for it).
    pub fn read_ms(&self, device: &wgpu::Device) -> Option<f64> {
        let slice = self.readback.slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
        receiver.recv().ok()?.ok()?;
        let stamps: Option<[u64; 2]> = slice
            .get_mapped_range()
            .ok()
            .map(|bytes| bytemuck::pod_read_unaligned(&bytes[..]));
        self.readback.unmap();
        let stamps = stamps?;
        let [begin, end] = stamps;
        (begin != 0 && end > begin).then(|| (end - begin) as f64 * self.period_ns * 1e-6)
    }
}

/// The frame time the controller sees: the GPU's reading when it is plausible (positive and
/// no longer than the wall time around it, with 0.1 ms of slack for clock granularity), else
/// the wall time.
pub fn frame_ms(gpu_ms: Option<f64>, wall_ms: f64) -> (f64, TimeSource) {
    match gpu_ms {
        Some(ms) if ms > 0.0 && ms <= wall_ms + 0.1 => (ms, TimeSource::Timestamps),
        _ => (wall_ms, TimeSource::WallClock),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plausible_reading_is_kept() {
        assert_eq!(frame_ms(Some(4.0), 5.0), (4.0, TimeSource::Timestamps));
    }

    #[test]
    fn missing_or_impossible_readings_fall_back_to_the_wall_time() {
        assert_eq!(frame_ms(None, 5.0), (5.0, TimeSource::WallClock));
        assert_eq!(frame_ms(Some(9.0), 5.0), (5.0, TimeSource::WallClock));
        assert_eq!(frame_ms(Some(0.0), 5.0), (5.0, TimeSource::WallClock));
    }
}
