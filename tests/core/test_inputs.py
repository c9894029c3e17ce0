import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.core.inputs import check_array


@pytest.mark.parametrize("make", [np.full, jnp.full])
def test_large_arrays_checked_on_either_side(make):
    """Large JAX arrays are summarized on the device; numpy ones on the host: same verdicts."""
    bad = make((128, 128), np.nan)
    with pytest.raises(ValueError, match="eta"):
        check_array("eta", bad)
    with pytest.raises(ValueError, match="eta must lie in"):
        check_array("eta", make((128, 128), -1.0), lo=0.0)
    check_array("eta", make((128, 128), 1.0), lo=0.0)
    with pytest.raises(TypeError, match="real"):
        check_array("eta", make((128, 128), 1j))
    with pytest.raises(TypeError, match="numeric"):
        check_array("eta", make((128, 128), True))
