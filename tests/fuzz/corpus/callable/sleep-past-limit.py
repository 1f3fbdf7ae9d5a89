# Issue 46: calls asleep in C past their limit gave every row ok; each is now a time-limit row.
def f(case):
    time.sleep(0.9)
    return {'status': 'ok', 'pi1': 1.0}
