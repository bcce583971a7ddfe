# usage: pcs.py BINARY -> prints every instrumented PC (link-time address, hex) from __sancov_pcs via .rela.dyn
import struct,sys,subprocess,re
b=sys.argv[1]
data=open(b,'rb').read()
secs={}
for line in subprocess.run(['readelf','-SW',b],capture_output=True,text=True).stdout.splitlines():
    m=re.match(r'\s*\[\s*\d+\]\s+(\S+)\s+\S+\s+([0-9a-f]+)\s+([0-9a-f]+)\s+([0-9a-f]+)',line)
    if m: secs[m.group(1)]=(int(m.group(2),16),int(m.group(3),16),int(m.group(4),16))
pa,po,ps=secs['__sancov_pcs']
ra,ro,rs=secs['.rela.dyn']
entries={}
for i in range(rs//24):
    o,info,add=struct.unpack_from('<QQq',data,ro+24*i)
    if pa<=o<pa+ps and (o-pa)%16==0 and (info&0xffffffff)==8:
        entries[o]=add
n=ps//16
print(f"# {n} pcs, {len(entries)} relocated",file=sys.stderr)
for k in range(n):
    a=entries.get(pa+16*k)
    if a is not None: print(hex(a))
