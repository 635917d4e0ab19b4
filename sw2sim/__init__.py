"""From a SolidWorks-exported URDF package to a MuJoCo simulation."""
