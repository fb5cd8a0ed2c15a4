"""The simulated table top: physics (`sim`), scenes (`scenes`) and the camera (`render`, `camera`)."""
