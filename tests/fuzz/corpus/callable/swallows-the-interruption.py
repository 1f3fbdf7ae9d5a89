# A call that catches TimeLimitExceeded and answers ok anyway: judged by its time, a time-limit row.
def f(case):
    try:
        busy(30.0)
    except BaseException:
        pass
    return {'status': 'ok', 'pi1': 1.0}
