"""The digital lock reference (seed 004 §4.8, §5.2.4.6): rigid, non-rigid, never lock, windows, ratio."""

from motiontool.apc.diglock import DigitalLock
from motiontool.apc.profile import ProfileGenerator

from .helpers import VirtualMaster, enabled_drive


def locking_drive(per_sample: int, rigid: bool, **kw):
    d = enabled_drive()
    vm = VirtualMaster(d, per_sample)
    if rigid:
        d.APCEnableRigidLock()
    for name, value in kw.items():
        getattr(d, name)(value)
    d.run_ms(20)                 # the master is running, the slave stands (Stop)
    return d, vm


def test_rigid_lock_ends_with_zero_net_position_loss():
    """L1791-1799 "the slave will ramp up to the maximum profile speed, to regain position lost during acceleration,
    then ramp down to the Master speed, and become locked": afterwards slave − ratio·master is what it was when the
    lock was selected."""
    d, _ = locking_drive(1000, rigid=True)
    before = d.read(117) - d.read(28)
    d.APCSelectReference(4)
    overspeed = 0
    for _ in range(3000):
        d.tick()
        overspeed = max(overspeed, d.read(118) - d.read(26))
        if d.read(61) == 1:
            break
    assert d.read(61) == 1 and overspeed > 0
    for _ in range(500):
        d.tick()
        assert d.read(117) - d.read(28) == before


def test_non_rigid_lock_keeps_a_constant_lag_equal_to_the_acceleration_loss():
    """L1763-1770 "No position will be recovered from when the Slave accelerated / decelerated to the Master
    speed": once locked the lag stays what the ramp lost, v²/(2a) for a master at speed v and accel a."""
    d, _ = locking_drive(1000, rigid=False)
    before = d.read(117) - d.read(28)
    d.APCSelectReference(4)
    while d.read(61) != 1:
        d.tick()
    lag = before - (d.read(117) - d.read(28))
    v = 1000 / 4                                 # counts per quarter (1 ms = 4 quarters)
    a = 22369 / 65536                            # default accel in counts per quarter²
    assert abs(lag - v * v / (2 * a)) <= 2 * v
    for _ in range(500):
        d.tick()
        assert before - (d.read(117) - d.read(28)) == lag


def test_lock_is_immediate_with_the_master_at_rest():
    """L1768-1769 "If the Slave is enabled when the Master is at zero speed, then the Slave will become locked
    directly"."""
    for rigid in (False, True):
        d, _ = locking_drive(0, rigid=rigid)
        d.APCSelectReference(4)
        d.tick()
        assert d.read(61) == 1


def test_never_lock_stays_2_and_smooths_a_master_step():
    """L1742-1762 "Never Lock … the profile generator will remain active, therefore any large changes in Reference
    position will be smoothed out"."""
    d, vm = locking_drive(0, rigid=True)
    d.APCSelectReference(4)
    d.tick()
    assert d.read(61) == 1              # selection always starts unlocked; at rest it locks at once
    d.APCSetDigLockMode(2)              # never lock: only by hand (L1758-1759)
    vm.per_sample = 500_000
    d.tick()
    vm.per_sample = 0
    speeds = []
    for _ in range(2000):
        d.tick()
        speeds.append(d.read(118))
    assert d.read(61) == 2
    assert max(speeds) <= d.read(113) + 1
    assert d.read(117) - d.read(28) == 0 or abs(d.read(117) - d.read(28)) <= 1


def test_ratio_24_over_10_locked_drifts_zero_counts_over_a_million_samples():
    """L1830-1840 "A Gearbox with a ratio of 2.4:1 … Numerator 24, Denominator 10 … any remainder from the numerator
    denominator calculation is retained"."""
    dl, pg = DigitalLock(), ProfileGenerator()
    dl.ratio.numerator, dl.ratio.denominator = 24, 10
    dl.engage(0)
    dl.mode = 1
    master = 0
    for k in range(1_000_000):
        step = 3 + k % 7
        master += step
        dl.step(step, pg, 4)
    assert pg.position == (master * 24 // 10 + 2**31) % 2**32 - 2**31


def samples_to_lock(**windows) -> int:
    d, _ = locking_drive(1000, rigid=True, **windows)
    d.APCSelectReference(4)
    for k in range(1, 5000):
        d.tick()
        if d.read(61) == 1:
            return k
    return 5000


def test_lock_mode_flips_to_locked_when_the_windows_hold():
    """L3747-3770 "The condition for locking is when the modulus of the difference between reference and feedback
    speed, is less than or equal to digital lock locking speed" (and, rigid, the position within [65]): wide windows
    lock earlier than narrow ones, and zero windows hold off the lock."""
    wide = samples_to_lock(APCSetDigLockLockingPosition=200_000, APCSetDigLockLockingSpeed=2_000_000)
    default = samples_to_lock()
    narrow = samples_to_lock(APCSetDigLockLockingPosition=0, APCSetDigLockLockingSpeed=0)
    assert wide < default <= narrow
