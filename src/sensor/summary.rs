//! A sensor's peaks over a run: the summary's `sensors` entries.

use serde::Serialize;

use crate::run::SensorSeries;

/// A sensor's peak readings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SensorSummary {
    /// Its name.
    pub name: String,
    /// Its kind, as a scenario names it.
    pub kind: &'static str,
    /// Its arm station, m (none for an encoder).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub station_m: Option<f64>,
    /// Per channel: the largest |reading| and when.
    pub channels: Vec<ChannelPeak>,
}

/// The largest |reading| of one channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelPeak {
    /// The channel with its unit (`axial_m_s2`, `moment_n_m`, ...).
    pub channel: &'static str,
    /// Largest |value|, in the channel's unit.
    pub peak_abs: f64,
    /// When, s.
    pub peak_time_s: f64,
}

impl SensorSummary {
    /// The peaks of one sensor's series at times `t_s`.
    pub fn of(series: &SensorSeries, t_s: &[f64]) -> Self {
        let kind = &series.sensor.kind;
        let channels =
            kind.channels()
                .iter()
                .enumerate()
                .map(|(k, def)| {
                    let (i, peak_abs) =
                        series.values.iter().enumerate().fold((0, 0.0_f64), |best, (i, v)| {
                            if v[k].abs() > best.1 { (i, v[k].abs()) } else { best }
                        });
                    ChannelPeak { channel: def.key, peak_abs, peak_time_s: t_s.get(i).copied().unwrap_or(0.0) }
                })
                .collect();
        SensorSummary { name: series.sensor.name.clone(), kind: kind.name(), station_m: kind.station_m(), channels }
    }
}
