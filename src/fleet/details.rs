//! What a fleet run reports besides its fleet metrics, defined once: the fleet planner writes
//! it into the run's `summary.json` (its planner-specific fields), and the command line, the
//! study's `runs.csv` and the report read it back through this type, never by key names of
//! their own.

use serde::{Deserialize, Serialize};

/// A map of a summary's planner-specific fields.
pub type Details = serde_json::Map<String, serde_json::Value>;

/// A fleet run's own fields.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FleetDetails {
    /// The fleet's label (`[fleet] name`), if it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fleet_name: Option<String>,
    /// What a negotiation adds (other fleet methods have none).
    #[serde(flatten)]
    pub negotiation: Option<Negotiation>,
}

/// The outcome of a negotiation between the robots' planners.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Negotiation {
    /// Rounds negotiated.
    pub rounds: u32,
    /// Whether the plans settled (no robot's plan changed by more than the tolerance).
    pub converged: bool,
    /// The largest change of a robot's plan in the last round (none before a round ended).
    pub last_round_change: Option<f64>,
}

impl FleetDetails {
    /// The fleet fields of a summary's planner-specific fields (defaults where absent).
    pub fn read(details: &Details) -> Self {
        serde_json::from_value(serde_json::Value::Object(details.clone())).unwrap_or_default()
    }

    /// Writes these fields into `details`, beside the planner's others.
    pub fn write_into(&self, details: &mut Details) {
        if let serde_json::Value::Object(own) = serde_json::to_value(self).expect("fleet details serialise") {
            details.extend(own);
        }
    }
}

impl Negotiation {
    /// The `runs.csv` fields of a negotiation: rounds, settled, last change (as JSON writes them).
    pub fn fields(&self) -> [String; 3] {
        let change = self.last_round_change.and_then(serde_json::Number::from_f64).map(|n| n.to_string());
        [self.rounds.to_string(), self.converged.to_string(), change.unwrap_or_default()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_round_trip_through_a_summary_and_absent_ones_read_as_none() {
        let full = FleetDetails {
            fleet_name: Some("pair".into()),
            negotiation: Some(Negotiation { rounds: 7, converged: true, last_round_change: Some(1e-5) }),
        };
        let mut details = Details::new();
        details.insert("mode".into(), "negotiate".into());
        full.write_into(&mut details);
        assert_eq!(details["rounds"], 7);
        assert_eq!(details["mode"], "negotiate");
        assert_eq!(FleetDetails::read(&details), full);
        let change = serde_json::Number::from_f64(1e-5).unwrap().to_string();
        assert_eq!(full.negotiation.unwrap().fields(), ["7".to_string(), "true".into(), change]);
        let mut divide = Details::new();
        divide.insert("angle_deg".into(), 90.0.into());
        assert_eq!(FleetDetails::read(&divide), FleetDetails::default());
    }
}
