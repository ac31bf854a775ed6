# Independent reference for the smoothdata window heuristic (classifier.md §1), with
# numpy's FFT instead of our Goertzel sweep. test_smoothing.cpp embeds its output.
# Run: /usr/bin/python3 tests/features/reference_windows.py
import numpy as np
def window(x,f):
    x=np.asarray(x,float); N=len(x); tau=1-f
    if np.ptp(x)==0: return 1
    c=x-x.mean()
    F=np.fft.fft(c,2*N); P=np.abs(F[:N])**2/(2*N)
    cdf=np.cumsum(P)/P.sum()
    rho=int(np.argmax(cdf>tau))+1
    w=np.ceil(np.sqrt((0.44294*2*N/max(rho-1,1))**2+1))
    return int(min(w,2*N))
def lcg(n,seed):
    out=[];s=seed
    for i in range(n):
        s=(s*6364136223846793005+1442695040888963407)%(1<<64)
        out.append(((s>>11)/(1<<53))-0.5)
    return np.array(out)
N=150; i=np.arange(N)
bump=0.4*np.exp(-0.5*((i-75)/12.0)**2)+0.008*lcg(N,7)
print("bump", window(bump,0.05), window(bump,0.25), window(bump,0.01))
ramp=np.arange(40)*1.0
print("ramp", window(ramp,0.05))
alt=np.array([(-1)**k for k in range(20)],float)
print("alt", window(alt,0.05))
step=np.r_[np.zeros(30),np.ones(30)]
print("step", window(step,0.05), window(step,0.5))
# shared: average of cdfs
def shared(cols,f):
    N=len(cols[0]);tau=1-f;cd=[]
    for x in cols:
        c=np.asarray(x,float);c=c-c.mean();F=np.fft.fft(c,2*N);P=np.abs(F[:N])**2/(2*N);cd.append(np.cumsum(P)/P.sum())
    m=np.mean(cd,axis=0);rho=int(np.argmax(m>tau))+1
    return int(min(np.ceil(np.sqrt((0.44294*2*N/max(rho-1,1))**2+1)),2*N))
b2=0.3*np.exp(-0.5*((i-60)/5.0)**2)+0.008*lcg(N,9)
print("shared", shared([bump,b2],0.05), window(b2,0.05))
print(lcg(3,7))
