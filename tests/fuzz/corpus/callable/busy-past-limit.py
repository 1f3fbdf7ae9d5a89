# Issue 46: a 30 s loop in Python at a limit of 0.3 s: interrupted (TimeLimitExceeded), a time-limit row.
STUDY = True
def f(case):
    busy(30.0)
    return {'status': 'ok', 'pi1': 1.0}
