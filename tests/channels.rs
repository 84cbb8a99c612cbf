//! The run's channels as their producers declare them (`pipearm::channel`), against the series the
//! run fills: on scenes that between them have every producer (the arm and its pad, a held string
//! flexible and friction-clamped, a tilting head, a servo, two cylinders, sensors, rig
//! structures), every declared channel reads a value at every step, every per-step history the
//! run fills is read by a channel, no name is declared twice, and every signal a measured file may
//! name is plotted (the recording draws a measured column over it).

use std::collections::BTreeSet;
use std::path::Path;

use pipearm::channel::Reading;
use pipearm::model::Model;
use pipearm::run::{Series, measurable_channels, run};
use pipearm::scenario::Scenario;
use pipearm::sensor::SensorSpec;

fn model(name: &str) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios").join(format!("{name}.toml"));
    Scenario::load(&path).unwrap().model
}

/// The per-step histories `series` filled, by the reading that reads each (one entry per
/// component of a vector history).
fn filled(series: &Series) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut add = |filled: bool, reading: String| {
        if filled {
            out.insert(reading);
        }
    };
    add(!series.hub_angle_rad.is_empty(), format!("{:?}", Reading::HubAngle));
    add(!series.actuator.is_empty(), format!("{:?}", Reading::HubReference));
    for k in 0..series.pad_force_n.len() {
        add(true, format!("{:?}", Reading::ContactForce(k)));
    }
    add(!series.head_angle_rad.is_empty(), format!("{:?}", Reading::HeadAngle));
    add(!series.head_drive_torque_n_m.is_empty(), format!("{:?}", Reading::HeadDriveTorque));
    add(!series.string_slip_m.is_empty(), format!("{:?}", Reading::StringSlip));
    add(!series.jaw_sinking_m.is_empty(), format!("{:?}", Reading::JawSinking));
    add(!series.string_tip_deflection_m.is_empty(), format!("{:?}", Reading::StringTipDeflection));
    add(!series.string_stress_pa.is_empty(), format!("{:?}", Reading::StringBendingStress));
    for (index, sensor) in series.sensors.iter().enumerate() {
        for channel in 0..2 {
            add(!sensor.values.is_empty(), format!("{:?}", Reading::Sensor { index, channel }));
        }
    }
    for i in 0..series.modal_dofs {
        add(true, format!("{:?}", Reading::Modal(i)));
    }
    out
}

/// The checks of the module doc on one run of `model`.
fn check(name: &str, model: &Model) {
    let (_, series) = run(model, None).unwrap_or_else(|e| panic!("{name}: {e}"));
    let steps = series.t_s.len();
    let mut names = BTreeSet::new();
    for channel in &series.channels {
        assert!(names.insert(channel.name.clone()), "{name}: `{}` declared twice", channel.name);
        let values = series.values(channel);
        assert_eq!(values.len(), steps, "{name}: `{}`", channel.name);
        assert!(values.iter().all(|v| v.is_finite()), "{name}: `{}` is not finite", channel.name);
    }
    let read: BTreeSet<String> = series.channels.iter().map(|c| format!("{:?}", c.reading())).collect();
    let unread: Vec<String> = filled(&series).into_iter().filter(|r| !read.contains(r)).collect();
    assert!(unread.is_empty(), "{name}: histories no channel reads: {unread:?}");
    for channel in measurable_channels(model) {
        assert!(channel.plot.is_some(), "{name}: `{}` is measurable but not plotted", channel.name);
        assert!(names.contains(&channel.name), "{name}: `{}` measurable but not run", channel.name);
    }
}

#[test]
fn every_declared_channel_reads_the_run_and_every_history_is_declared() {
    for name in ["default", "friction_clamp", "tilting_head", "servo", "hydraulic_twin", "string_strike"] {
        check(name, &model(name));
    }
    let mut with_sensors = model("default");
    let sensor = |name: &str, kind: &str, station_m| {
        SensorSpec { name: name.into(), kind: kind.into(), station_m }.resolve(&with_sensors.robot).unwrap()
    };
    let sensors = vec![sensor("root", "strain-gauge", Some(0.0)), sensor("encoder", "encoder", None)];
    with_sensors.sensors = sensors;
    check("default with sensors", &with_sensors);
}

#[test]
fn a_sensor_may_not_spell_another_channels_name() {
    let model = model("tilting_head");
    // An encoder named `head` would read `head.angle`, the head's own channel.
    let spec = SensorSpec { name: "head".into(), kind: "encoder".into(), station_m: None };
    let (key, message) = spec.resolve(&model.robot).unwrap_err();
    assert_eq!(key, "name");
    assert!(message.contains("other than") && message.contains("head"), "{message}");
}
