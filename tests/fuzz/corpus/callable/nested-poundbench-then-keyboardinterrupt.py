# Issue 46: a function that calls poundbench itself, then raises KeyboardInterrupt: the sweep must stop.
calls = [0]
def f(case):
    calls[0] += 1
    poundbench.run(scene='wall', pulse='sine', directivity='normal', pi2=1, pi3=0.5, eps=0.5, solver='moreau-jean', steps=16)
    poundbench.spectrum(SET, solver=lambda c: {'status': 'ok', 'pi1': 1.0})
    if calls[0] == 2:
        raise KeyboardInterrupt()
    return {'status': 'ok', 'pi1': 1.0}
